//! The 16-bit mapping of heights (PNG, `.r16` outside Unreal's encoding, foam maps aside).

use serde::Serialize;

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
        // round then clamp = clamp then round (the bounds are integers), and rounding a
        // clamped value needs no library call.
        let v = ((h as f64 - self.min_m) / span * 65535.0).clamp(0.0, 65535.0);
        crate::fastmath::round_nonneg_f64(v) as u16
    }

    pub fn decode(&self, v: u16) -> f64 {
        self.min_m + v as f64 * self.step_m()
    }
}
