//! Maps of a wave state besides the height: tangent-space normals, foam, the Jacobian of
//! the choppy displacement and the displacement itself. All are indexed by the
//! undisplaced grid (sample (i, j) at x = i·dx, y = j·dy, row j = image row j), as a
//! displacement-mapped mesh uses them.
//!
//! | output name | content |
//! |---|---|
//! | `NAME.normal.png` | 8-bit RGB normal map: (r, g, b) = round(255·(n + 1)/2) with n = (nx, ny, nz), nx along +x (image right), ny along +y (image row index increasing), nz up. This is the OpenGL (+Y, "green up") convention when the image is loaded with row 0 at v = 0, as OpenGL does; flip green for DirectX. |
//! | `NAME.foam.png` | 16-bit gray foam coverage: round(65535·clamp((T − J)/T, 0, 1)) with T the foam threshold (`auto`: the quantile of J that covers the wind's whitecap fraction, [`crate::measure::foam`]): 0 where J ≥ T, full where the surface folds (J ≤ 0); in an animation with `--foam-fade`, the persistent foam |
//! | `NAME.jacobian.tif` | 32-bit float J (1: undisturbed, < 0: folded) |
//! | `NAME.disp.tif` | 32-bit float RGB: (λDx, λDy, h) in meters, the vertex displacement of choppy waves |
//!
//! Each is also written as float EXR by the outer extension `.exr` (`NAME.disp.exr`, …):
//! see [`super::exr`] for the channels. The displacement EXR is in the output's axis
//! convention (`--up`), so that a host's vector displacement applies it as it is.

use std::io::{Seek, Write};

use rayon::prelude::*;
use tiff::encoder::{TiffEncoder, colortype};

pub use super::format::{MapEncoding, MapKind};
use crate::grid::GridSpec;
pub use crate::measure::foam::{
    FoamRule, ResolvedFoam, coverage as foam_coverage, coverage_u16 as foam_value,
};
use crate::simd::{Isa, multiversion};

/// What a wave-state map needs besides the state.
pub struct MapContext<'a> {
    pub params: &'a crate::config::Params,
    pub synthesis: &'a crate::field::Synthesis,
    /// The axis convention of a displacement EXR.
    pub up: super::options::UpAxis,
    /// How EXR maps are written.
    pub exr: super::exr::ExrOptions,
    /// The foam threshold T, resolved (an animation's, for the whole sequence); `None`:
    /// resolved from this field's J by [`FoamRule::of`] the parameters.
    pub foam_threshold: Option<f64>,
    /// The foam of an animation that persists and fades (16-bit coverage,
    /// `pipeline::foam_fade`), in place of this field's own.
    pub persistent_foam: Option<&'a [u16]>,
}

impl MapContext<'_> {
    /// The foam threshold of these maps over the J samples `j`.
    fn threshold(&self, j: &[f32]) -> f64 {
        self.foam_threshold
            .unwrap_or_else(|| FoamRule::of(self.params).resolve(j).threshold)
    }

    /// The 16-bit foam coverage of the samples `j`.
    fn foam_u16(&self, j: &[f32]) -> Vec<u16> {
        match self.persistent_foam {
            Some(p) => p.to_vec(),
            None => {
                let t = self.threshold(j);
                j.par_iter().map(|&j| foam_value(j, t)).collect()
            }
        }
    }

    /// The foam coverage 0..1 of the samples `j`.
    fn foam_f32(&self, j: &[f32]) -> Vec<f32> {
        match self.persistent_foam {
            Some(p) => p.iter().map(|&v| v as f32 / 65535.0).collect(),
            None => {
                let t = self.threshold(j);
                j.par_iter().map(|&j| foam_coverage(j, t)).collect()
            }
        }
    }
}

/// The foam coverage 0..1 at every grid point of a synthesized field and the threshold
/// that made it (`motion.foam_threshold` resolved over this field's J), or `None` when
/// the synthesis has no Jacobian (synthesize with `Extras { jacobian: true, .. }`).
pub fn foam_coverage_of(
    params: &crate::config::Params,
    synthesis: &crate::field::Synthesis,
) -> Option<(Vec<f32>, ResolvedFoam)> {
    let j = synthesis
        .surface
        .jacobian
        .as_ref()?
        .values(synthesis.grid.spec.len());
    let foam = FoamRule::of(params).resolve(&j);
    let c = j
        .iter()
        .map(|&j| foam_coverage(j, foam.threshold))
        .collect();
    Some((c, foam))
}

/// The foam coverage 0..1 at every grid point of a synthesis (which computed the
/// Jacobian, or is not choppy) at the threshold `threshold`: a foam EXR's values.
pub fn foam_coverage_at(synthesis: &crate::field::Synthesis, threshold: f64) -> Vec<f32> {
    let len = synthesis.grid.spec.len();
    match synthesis.surface.jacobian.as_ref() {
        Some(j) => j
            .values(len)
            .par_iter()
            .map(|&j| foam_coverage(j, threshold))
            .collect(),
        None => vec![foam_coverage(1.0, threshold); len],
    }
}

/// The derived fields the given maps need (a displacement EXR carries foam when the sea
/// is choppy).
pub fn extras_for(kinds: &[(MapKind, MapEncoding)]) -> crate::field::dynamics::Extras {
    let mut e = crate::field::dynamics::Extras::default();
    for k in kinds {
        match k {
            (MapKind::Normal, _) => e.slopes = true,
            (MapKind::Foam | MapKind::Jacobian, _) => e.jacobian = true,
            (MapKind::Displacement, enc) => {
                e.displacement = true;
                e.jacobian |= *enc == MapEncoding::Exr;
            }
        }
    }
    e
}

/// The channels of a displacement EXR: R, G, B = (λDx, h, −λDy) for `--up y`, (λDx, λDy,
/// h) for `--up z`.
pub fn displacement_channels(
    up: super::options::UpAxis,
    dx: &[f32],
    dy: &[f32],
    h: &[f32],
) -> [Vec<f32>; 3] {
    match up {
        super::options::UpAxis::Y => [dx.to_vec(), h.to_vec(), dy.iter().map(|v| -v).collect()],
        super::options::UpAxis::Z => [dx.to_vec(), dy.to_vec(), h.to_vec()],
    }
}

/// Writes the map `kind` of a synthesis to `staged`, as its usual image or as EXR.
pub fn write_map(
    kind: MapKind,
    encoding: MapEncoding,
    staged: super::Staged,
    cx: &MapContext,
) -> crate::error::Result<()> {
    let syn = cx.synthesis;
    let spec = syn.grid.spec;
    let surf = &syn.surface;
    let missing = || crate::error::Error::Output {
        path: staged.path.clone(),
        message: "the state has no such field".into(),
    };
    if encoding == MapEncoding::Exr {
        return write_map_exr(kind, staged, cx);
    }
    match kind {
        MapKind::Normal => {
            let normals = surf.normals().ok_or_else(missing)?;
            let rgb = normal_rgb(&normals);
            super::rgb8::write_map(staged, &rgb, (spec.nx as u32, spec.ny as u32))
        }
        MapKind::Foam => {
            let j = surf
                .jacobian
                .as_ref()
                .ok_or_else(missing)?
                .values(spec.len());
            let v = cx.foam_u16(&j);
            staged.write_with(|w| write_gray16(w, &spec, &v))
        }
        MapKind::Jacobian => {
            let j = surf
                .jacobian
                .as_ref()
                .ok_or_else(missing)?
                .values(spec.len());
            staged.write_with(|w| write_f32(w, &spec, &j))
        }
        MapKind::Displacement => {
            let zero;
            let [dx, dy] = match surf.displacement.as_ref() {
                Some(d) => [&d[0], &d[1]],
                None => {
                    zero = vec![0.0f32; spec.len()];
                    [&zero, &zero]
                }
            };
            let h = surf.undisplaced_height.as_deref().unwrap_or(&syn.grid.data);
            staged.write_with(|w| write_xyz_f32(w, &spec, dx, dy, h))
        }
    }
}

/// Writes the map `kind` as float EXR (channels in [`super::exr`]).
fn write_map_exr(
    kind: MapKind,
    staged: super::Staged,
    cx: &MapContext,
) -> crate::error::Result<()> {
    use super::exr::write_channels;
    let syn = cx.synthesis;
    let spec = syn.grid.spec;
    let size = (spec.nx, spec.ny);
    let surf = &syn.surface;
    let missing = || crate::error::Error::Output {
        path: staged.path.clone(),
        message: "the state has no such field".into(),
    };
    let jacobian = surf.jacobian.as_ref().map(|j| j.values(spec.len()));
    match kind {
        MapKind::Normal => {
            let normals = surf.normals().ok_or_else(missing)?;
            let c: Vec<Vec<f32>> = (0..3)
                .map(|k| normals.iter().map(|n| n[k]).collect())
                .collect();
            let ch = [("R", &c[0][..]), ("G", &c[1][..]), ("B", &c[2][..])];
            let note = "unit normal (nx, ny, nz): nx along +x, ny along +y (row index), nz up";
            staged.write_with(|w| write_channels(w, size, &ch, cx.exr, note))
        }
        MapKind::Foam => {
            let j = jacobian.ok_or_else(missing)?;
            let f = cx.foam_f32(&j);
            let note = "foam coverage 0..1 = clamp((T - J)/T, 0, 1)";
            staged.write_with(|w| write_channels(w, size, &[("Y", &f)], cx.exr, note))
        }
        MapKind::Jacobian => {
            let j = jacobian.ok_or_else(missing)?;
            let note = "Jacobian J of the choppy displacement (1: undisturbed, < 0: folded)";
            staged.write_with(|w| write_channels(w, size, &[("Y", &j)], cx.exr, note))
        }
        MapKind::Displacement => {
            let zero;
            let [dx, dy] = match surf.displacement.as_ref() {
                Some(d) => [&d[0], &d[1]],
                None => {
                    zero = vec![0.0f32; spec.len()];
                    [&zero, &zero]
                }
            };
            let h = surf.undisplaced_height.as_deref().unwrap_or(&syn.grid.data);
            let [r, g, b] = displacement_channels(cx.up, dx, dy, h);
            // Foam only where the displacement can fold the surface.
            let foam: Option<Vec<f32>> = jacobian
                .filter(|_| cx.params.motion.choppiness != 0.0)
                .map(|j| cx.foam_f32(&j));
            let mut ch = vec![("R", &r[..]), ("G", &g[..]), ("B", &b[..])];
            if let Some(f) = &foam {
                ch.push(("A", &f[..]));
            }
            let note = match cx.up {
                super::options::UpAxis::Y => {
                    "displacement (R, G, B) = (x, height, -y) in meters, Y up; A = foam"
                }
                super::options::UpAxis::Z => {
                    "displacement (R, G, B) = (x, y, height) in meters, Z up; A = foam"
                }
            };
            staged.write_with(|w| write_channels(w, size, &ch, cx.exr, note))
        }
    }
}

/// The 8-bit RGB bytes of a normal map: each component c to round((clamp(c, −1, 1) + 1)/2
/// · 255), in parallel blocks compiled for the processor's vector instructions.
pub fn normal_rgb(normals: &[[f32; 3]]) -> Vec<u8> {
    normal_rgb_on(Isa::detect(), normals)
}

/// [`normal_rgb`] on the instruction set `isa` (every one gives the same bytes).
pub(crate) fn normal_rgb_on(isa: Isa, normals: &[[f32; 3]]) -> Vec<u8> {
    let c = normals.as_flattened();
    let mut rgb = vec![0u8; c.len()];
    rgb.par_chunks_mut(3 * 16384)
        .zip(c.par_chunks(3 * 16384))
        .for_each(|(out, c)| normal_bytes(isa, c, out));
    rgb
}

multiversion! {
    @on
    /// The bytes of [`normal_rgb`]. Clamping (c + 1)/2·255 to 0..=255 is clamping c to
    /// −1..=1 first (the map is monotone and takes ±1 to 0 and 255 exactly).
    fn normal_bytes(isa: Isa, c: &[f32], out: &mut [u8]) {
        for (o, &c) in out.iter_mut().zip(c) {
            *o = crate::fastmath::round_clamped_f32((c + 1.0) * 0.5 * 255.0, 255.0) as u8;
        }
    }
}

/// A 16-bit grayscale PNG of `values` (row-major, `spec.nx` wide).
pub fn write_gray16<W: Write>(w: W, spec: &GridSpec, values: &[u16]) -> std::io::Result<()> {
    use super::png_par::{Layout, PngWriter};
    let mut png = PngWriter::new(w, (spec.nx, spec.ny), Layout::Gray16, &[])?;
    let rows = spec.nx * 256;
    let mut bytes = vec![0u8; 2 * rows];
    for values in values.chunks(rows) {
        let bytes = &mut bytes[..2 * values.len()];
        bytes
            .par_chunks_mut(2 * 16384)
            .zip(values.par_chunks(16384))
            .for_each(|(out, v)| {
                for (o, v) in out.chunks_exact_mut(2).zip(v) {
                    o.copy_from_slice(&v.to_be_bytes());
                }
            });
        png.write_rows(bytes)?;
    }
    png.finish()?.flush()
}

/// A one-channel f32 TIFF.
pub fn write_f32<W: Write + Seek>(w: W, spec: &GridSpec, values: &[f32]) -> std::io::Result<()> {
    let mut enc = TiffEncoder::new(w).map_err(std::io::Error::other)?;
    enc.write_image::<colortype::Gray32Float>(spec.nx as u32, spec.ny as u32, values)
        .map_err(std::io::Error::other)
}

/// A three-channel f32 TIFF of (x, y, z) per sample.
pub fn write_xyz_f32<W: Write + Seek>(
    w: W,
    spec: &GridSpec,
    x: &[f32],
    y: &[f32],
    z: &[f32],
) -> std::io::Result<()> {
    // Interleaved in parallel, a row per task, into memory not zeroed first.
    let (nx, len) = (spec.nx, 3 * spec.len());
    assert!(
        [x.len(), y.len(), z.len()].iter().all(|&n| n == spec.len()),
        "one sample per grid point"
    );
    let mut data: Vec<f32> = Vec::with_capacity(len);
    data.spare_capacity_mut()[..len]
        .par_chunks_mut(3 * nx)
        .zip(x.par_chunks(nx).zip(y.par_chunks(nx)).zip(z.par_chunks(nx)))
        .for_each(|(out, ((x, y), z))| {
            for (o, ((&a, &b), &c)) in out.chunks_exact_mut(3).zip(x.iter().zip(y).zip(z)) {
                o[0].write(a);
                o[1].write(b);
                o[2].write(c);
            }
        });
    // SAFETY: the rows of x, y and z (each nx long) fill every element of `len`.
    unsafe { data.set_len(len) };
    let mut enc = TiffEncoder::new(w).map_err(std::io::Error::other)?;
    enc.write_image::<colortype::RGB32Float>(spec.nx as u32, spec.ny as u32, &data)
        .map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn map_names_follow_the_inner_extension() {
        assert_eq!(
            MapKind::from_path(Path::new("a/x.normal.png")),
            Ok(Some(MapKind::Normal))
        );
        assert_eq!(
            MapKind::from_path(Path::new("x.DISP.tiff")),
            Ok(Some(MapKind::Displacement))
        );
        assert_eq!(MapKind::from_path(Path::new("x.png")), Ok(None));
        assert_eq!(MapKind::from_path(Path::new("my.sea.png")), Ok(None));
        let e = MapKind::from_path(Path::new("x.foam.tif")).unwrap_err();
        assert!(e.contains(".foam.png"), "{e}");
    }

    #[test]
    fn normal_bytes_are_the_clamped_rounded_components_on_every_instruction_set() {
        // Components at and next to every half step of a byte, past ±1, and non-finite.
        let mut c: Vec<f32> = vec![f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0, 0.0];
        c.extend([
            -1.0,
            1.0,
            (-1.0f32).next_down(),
            1.0f32.next_up(),
            -7.0,
            7.0,
        ]);
        for k in 0..=255 {
            let x = (k as f32 + 0.5) / 127.5 - 1.0;
            c.extend([x, x.next_down(), x.next_up()]);
        }
        c.extend((0..10_001).map(|i| (i as f32 * 1.3e-3).sin()));
        while c.len() % 3 != 0 {
            c.push(0.25);
        }
        let want: Vec<u8> = c
            .iter()
            .map(|&c| ((c.clamp(-1.0, 1.0) + 1.0) * 0.5 * 255.0).round() as u8)
            .collect();
        let normals: Vec<[f32; 3]> = c.chunks_exact(3).map(|n| [n[0], n[1], n[2]]).collect();
        for isa in Isa::available() {
            let got = normal_rgb_on(isa, &normals);
            let first = got.iter().zip(&want).position(|(a, b)| a != b);
            assert!(first.is_none(), "{isa:?}: byte {first:?} differs");
        }
    }

    #[test]
    fn normals_and_foam_encode_their_documented_ranges() {
        assert_eq!(normal_rgb(&[[0.0, 0.0, 1.0]]), vec![128, 128, 255]);
        assert_eq!(normal_rgb(&[[-1.0, 1.0, 0.0]]), vec![0, 255, 128]);
        assert_eq!(foam_value(1.0, 0.3), 0);
        assert_eq!(foam_value(0.3, 0.3), 0);
        assert_eq!(foam_value(0.25, 0.5), 32768);
        assert_eq!(foam_value(-0.5, 0.3), 65535);
    }
}
