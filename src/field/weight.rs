//! The FFT weight α(x, y) of the hybrid blend (Li Tian eq. 10), evaluated row by row.

use std::path::Path;

use crate::config::{AlphaConfig, AlphaFit, Axis};
use crate::error::{Error, Result};
use crate::grid::GridSpec;

/// α on a grid, in [0, 1].
pub enum AlphaMap {
    Constant(f32),
    /// α = 1 − (c/L)^power along one axis; `values` indexed by that axis' sample index.
    Ramp {
        axis: Axis,
        values: Vec<f32>,
    },
    Radial {
        spec: GridSpec,
        center_m: [f64; 2],
        radius_m: f64,
        power: f64,
    },
    /// Row-major samples, already resampled to the grid.
    Sampled {
        nx: usize,
        values: Vec<f32>,
    },
}

impl AlphaMap {
    /// Builds the map for `spec`; an image is read and resampled here.
    pub fn new(cfg: &AlphaConfig, spec: &GridSpec) -> Result<Self> {
        Self::with_offset(cfg, spec, 0.0)
    }

    /// [`new`](Self::new) for samples at ((i + offset)·dx, (j + offset)·dy): offset ½ for
    /// `--sample-at centers` (ramps and radial maps; an α image is refused, as its pixels
    /// are taken to be the grid's samples).
    pub fn with_offset(cfg: &AlphaConfig, spec: &GridSpec, offset: f64) -> Result<Self> {
        Ok(match cfg {
            AlphaConfig::Constant { value } => AlphaMap::Constant(*value as f32),
            AlphaConfig::Ramp { axis, power } => {
                let (n, l, step) = match axis {
                    Axis::X => (spec.nx, spec.extent_x_m, spec.dx_m()),
                    Axis::Y => (spec.ny, spec.extent_y_m, spec.dy_m()),
                };
                let values = (0..n)
                    .map(|i| (1.0 - ((i as f64 + offset) * step / l).powf(*power)) as f32)
                    .collect();
                AlphaMap::Ramp {
                    axis: *axis,
                    values,
                }
            }
            AlphaConfig::Radial {
                power,
                center_m,
                radius_m,
            } => AlphaMap::Radial {
                spec: *spec,
                // Moving the centre by −offset cells moves the samples by +offset.
                center_m: {
                    let c = center_m.unwrap_or([spec.extent_x_m / 2.0, spec.extent_y_m / 2.0]);
                    [c[0] - offset * spec.dx_m(), c[1] - offset * spec.dy_m()]
                },
                radius_m: radius_m.unwrap_or(spec.extent_x_m.min(spec.extent_y_m) / 2.0),
                power: *power,
            },
            AlphaConfig::Image { .. } if offset != 0.0 => {
                return Err(crate::error::Error::Set {
                    origin: "--sample-at centers".into(),
                    message: "an α image gives α at the grid's samples; use --sample-at \
                              corners with blend.alpha from an image"
                        .into(),
                });
            }
            AlphaConfig::Image { path, fit } => {
                let img = read_gray(path)?;
                if *fit == AlphaFit::Match {
                    check_aspect(path, &img, spec)?;
                }
                AlphaMap::Sampled {
                    nx: spec.nx,
                    values: resample(&img, spec.nx, spec.ny),
                }
            }
        })
    }

    /// Writes α of row `j` into `out` (length nx).
    pub fn row(&self, j: usize, out: &mut [f32]) {
        match self {
            AlphaMap::Constant(v) => out.fill(*v),
            AlphaMap::Ramp {
                axis: Axis::Y,
                values,
            } => out.fill(values[j]),
            AlphaMap::Ramp {
                axis: Axis::X,
                values,
            } => out.copy_from_slice(values),
            AlphaMap::Radial {
                spec,
                center_m,
                radius_m,
                power,
            } => {
                let dy = spec.y_m(j) - center_m[1];
                for (i, o) in out.iter_mut().enumerate() {
                    let dx = spec.x_m(i) - center_m[0];
                    let r = (dx * dx + dy * dy).sqrt() / radius_m;
                    *o = (1.0 - r.min(1.0).powf(*power)) as f32;
                }
            }
            AlphaMap::Sampled { nx, values } => out.copy_from_slice(&values[j * nx..(j + 1) * nx]),
        }
    }
}

/// A grayscale image with values in [0, 1].
pub struct GrayImage {
    pub width: usize,
    pub height: usize,
    pub values: Vec<f32>,
}

/// Reads an image as gray values in [0, 1] through `image` (`raster::read_raster`): any
/// format read there, gray or color by its Rec. 709 luma (alpha ignored), integer samples
/// as a fraction of their largest value, float samples clamped to [0, 1].
pub fn read_gray(path: &Path) -> Result<GrayImage> {
    let bad = |message: String| Error::Input {
        path: path.to_path_buf(),
        message,
    };
    let r = crate::raster::read_raster(path).map_err(|m| bad(format!("α image: {m}")))?;
    if let Some(i) = r.values.iter().position(|v| !v.is_finite()) {
        return Err(bad(format!(
            "α image sample (x {}, row {}) is {}: α must be finite",
            i % r.width,
            i / r.width,
            r.values[i]
        )));
    }
    let values = match r.integer_bits {
        Some(_) => r.values,
        None => r.values.into_iter().map(|v| v.clamp(0.0, 1.0)).collect(),
    };
    Ok(GrayImage {
        width: r.width,
        height: r.height,
        values,
    })
}

/// Refuses an image whose aspect ratio is not the extent's, within a pixel on either side.
fn check_aspect(path: &Path, img: &GrayImage, spec: &GridSpec) -> Result<()> {
    let (w, h) = (img.width as f64, img.height as f64);
    let (ex, ey) = (spec.extent_x_m, spec.extent_y_m);
    if (h - w * ey / ex).abs() <= 1.0 || (w - h * ex / ey).abs() <= 1.0 {
        return Ok(());
    }
    Err(Error::Param(crate::error::ParamError {
        name: "blend.alpha.path".into(),
        allowed: format!(
            "an image of the extent's aspect ratio, {ex} m × {ey} m ({:.4}), or blend.alpha.fit = \"stretch\"",
            ex / ey
        ),
        got: format!(
            "{}: {}×{} pixels ({:.4})",
            path.display(),
            img.width,
            img.height,
            w / h
        ),
    }))
}

/// Bilinear resampling with pixel centers aligned (an image of the grid's size is copied
/// exactly); edges are clamped.
pub fn resample(img: &GrayImage, nx: usize, ny: usize) -> Vec<f32> {
    let coord = |i: usize, n: usize, m: usize| -> (usize, usize, f32) {
        let u = ((i as f64 + 0.5) * m as f64 / n as f64 - 0.5).clamp(0.0, (m - 1) as f64);
        let i0 = u.floor() as usize;
        (i0, (i0 + 1).min(m - 1), (u - i0 as f64) as f32)
    };
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let (j0, j1, ty) = coord(j, ny, img.height);
        for i in 0..nx {
            let (i0, i1, tx) = coord(i, nx, img.width);
            let at = |a: usize, b: usize| img.values[b * img.width + a];
            let top = at(i0, j0) + (at(i1, j0) - at(i0, j0)) * tx;
            let bot = at(i0, j1) + (at(i1, j1) - at(i0, j1)) * tx;
            out.push(top + (bot - top) * ty);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(map: &AlphaMap, j: usize, nx: usize) -> Vec<f32> {
        let mut r = vec![0.0; nx];
        map.row(j, &mut r);
        r
    }

    const TOL: f32 = 1e-6;

    #[test]
    fn ramp_edges_and_corners_follow_the_formula() {
        let spec = GridSpec::new(8, 16, 80.0, 160.0);
        let m = AlphaMap::new(
            &AlphaConfig::Ramp {
                axis: Axis::Y,
                power: 3.0,
            },
            &spec,
        )
        .unwrap();
        assert_eq!(row(&m, 0, 8), vec![1.0; 8], "α = 1 at y = 0");
        let last = 1.0 - (15.0f64 / 16.0).powi(3);
        for (i, v) in row(&m, 15, 8).iter().enumerate() {
            assert!(
                (v - last as f32).abs() < TOL,
                "last row, column {i}: {v} vs {last}"
            );
        }
        let mid = 1.0 - 0.5f64.powi(3);
        assert!((row(&m, 8, 8)[3] - mid as f32).abs() < TOL);
        let mx = AlphaMap::new(
            &AlphaConfig::Ramp {
                axis: Axis::X,
                power: 2.0,
            },
            &spec,
        )
        .unwrap();
        let r = row(&mx, 5, 8);
        assert_eq!(r[0], 1.0);
        assert!((r[7] - (1.0 - (7.0f32 / 8.0).powi(2))).abs() < TOL);
        assert!((r[4] - 0.75).abs() < TOL);
    }

    #[test]
    fn radial_is_one_at_the_center_and_zero_beyond_the_radius() {
        let spec = GridSpec::new(10, 10, 10.0, 10.0);
        let cfg = AlphaConfig::Radial {
            power: 2.0,
            center_m: Some([5.0, 5.0]),
            radius_m: Some(4.0),
        };
        let m = AlphaMap::new(&cfg, &spec).unwrap();
        assert_eq!(row(&m, 5, 10)[5], 1.0, "the center sample (5 m, 5 m)");
        assert_eq!(row(&m, 0, 10)[0], 0.0, "corner is beyond the radius");
        assert!((row(&m, 5, 10)[7] - 0.75).abs() < TOL, "r = 2 m = radius/2");
        for j in 0..10 {
            for (i, v) in row(&m, j, 10).iter().enumerate() {
                let d = ((spec.x_m(i) - 5.0).powi(2) + (spec.y_m(j) - 5.0).powi(2)).sqrt();
                let want = 1.0 - (d / 4.0).min(1.0).powi(2);
                assert!((v - want as f32).abs() < TOL, "({i},{j})");
            }
        }
    }

    #[test]
    fn resampling_an_image_of_the_grid_size_copies_it_and_interpolates_otherwise() {
        let img = GrayImage {
            width: 2,
            height: 2,
            values: vec![0.0, 1.0, 0.5, 0.25],
        };
        assert_eq!(resample(&img, 2, 2), img.values);
        let up = resample(&img, 4, 4);
        assert_eq!(up[0], 0.0, "clamped corner");
        assert_eq!(up[3], 1.0);
        // Sample (1, 0) sits at u = 0.25: a quarter of the way from 0 to 1.
        assert!((up[1] - 0.25).abs() < TOL);
    }
}
