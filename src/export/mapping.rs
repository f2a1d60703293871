//! The 16-bit mapping of heights (PNG, `.r16` outside Unreal's encoding, foam maps aside).

use serde::Serialize;

use crate::simd::{Isa, multiversion};

/// The linear map from heights to 16-bit values: v = round((h − min_m)/(max_m − min_m)·65535),
/// clamped to 0..65535. A flat field (min = max) maps to 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeightMapping {
    pub min_m: f64,
    pub max_m: f64,
}

impl HeightMapping {
    /// The 16-bit mapping of a field and where it came from (for the sidecar): the given
    /// height range (`range_source`, e.g. "--height-range"), else the field's min..max
    /// (`field()`, asked for only then).
    pub fn choose(
        range: Option<crate::config::Range2>,
        range_source: &'static str,
        field: impl FnOnce() -> crate::grid::Stats,
    ) -> (HeightMapping, &'static str) {
        match range {
            Some(r) => (
                HeightMapping {
                    min_m: r.0[0],
                    max_m: r.0[1],
                },
                range_source,
            ),
            None => {
                let s = field();
                (
                    HeightMapping {
                        min_m: s.min_m,
                        max_m: s.max_m,
                    },
                    "field min..max",
                )
            }
        }
    }

    /// Meters per 16-bit step.
    pub fn step_m(&self) -> f64 {
        (self.max_m - self.min_m) / 65535.0
    }

    #[inline]
    pub fn encode(&self, h: f32) -> u16 {
        let span = self.max_m - self.min_m;
        if span <= 0.0 {
            return 0;
        }
        // round then clamp = clamp then round (the bounds are integers).
        crate::fastmath::round_clamped_f64((h as f64 - self.min_m) / span * 65535.0, 65535.0) as u16
    }

    /// [`HeightMapping::encode`] of every height of `heights`, as big-endian bytes (two a
    /// height) into `out`, compiled for the processor's vector instructions: the same IEEE
    /// operations in the same order (a vector division rounds as the scalar one), so the
    /// same values.
    ///
    /// # Panics
    /// If `out` is not twice as long as `heights`.
    pub fn encode_be(&self, heights: &[f32], out: &mut [u8]) {
        self.encode_be_on(Isa::detect(), heights, out);
    }

    /// [`HeightMapping::encode_be`] on the instruction set `isa`.
    pub(crate) fn encode_be_on(&self, isa: Isa, heights: &[f32], out: &mut [u8]) {
        assert_eq!(out.len(), 2 * heights.len(), "two bytes per height");
        let span = self.max_m - self.min_m;
        // `encode`'s flat field (and a NaN span, which it maps to 0 too).
        if span.is_nan() || span <= 0.0 {
            out.fill(0);
            return;
        }
        encode_be_run(isa, self.min_m, span, heights, out);
    }

    pub fn decode(&self, v: u16) -> f64 {
        self.min_m + v as f64 * self.step_m()
    }
}

multiversion! {
    @on
    /// The loop of [`HeightMapping::encode_be`] (`span` > 0): `encode`'s arithmetic.
    fn encode_be_run(isa: Isa, min_m: f64, span: f64, heights: &[f32], out: &mut [u8]) {
        for (o, &h) in out.chunks_exact_mut(2).zip(heights) {
            let v = (h as f64 - min_m) / span * 65535.0;
            let r = crate::fastmath::round_clamped_f64(v, 65535.0) as u16;
            o[0] = (r >> 8) as u8;
            o[1] = r as u8;
        }
    }
}
