//! The preview renderer: a shaded perspective view of a height field (`seasynth render`, `NAME.preview.png`).
//!
//! Rays are cast from a pinhole [`Camera`] through several points of every pixel
//! (`spp`, a fixed stratified pattern) and intersected with the field's bilinear surface,
//! skipping empty space with a max-height quadtree as in Mastin et al. (1987)
//! ([`trace`], [`pyramid`]); far away the surface is low-passed to the ray's footprint by
//! mean mip levels, so the horizon does not shimmer. Normals come from the slopes
//! ∂h/∂x, ∂h/∂y: central differences of the samples, or exact slope arrays when the caller
//! has them. Each hit is lit after Li, He & Gong (2015) with a Fresnel-weighted sky
//! reflection ([`shade`]), foam coverage drawn as whitecaps, or as terrain (diffuse rock,
//! grass and snow) for terrains. A periodic field repeats to the horizon; any other sits in
//! a flat sea at its mean height. The default views are framed by the field's peak
//! wavelength ([`peak_wavelength_m`]), so the steepness of the sea shows.
//!
//! Conventions are in [`camera`] (axes, yaw, pitch) and [`shade`] (colors). Every pixel is
//! computed on its own by the same operations whatever the number of threads, so images
//! are identical bytes for identical inputs.

pub mod camera;
pub mod pyramid;
pub mod shade;
pub mod trace;

use rayon::prelude::*;

pub use camera::{Camera, Projection, Scene, VIEWS, View};
pub use shade::{HeightScale, Lighting, Reflection};

use crate::error::{Error, ParamError};
use crate::grid::Grid;
use pyramid::{Pyramid, central_slopes};
use trace::{Lod, Ray, Tracer};

/// Largest image side, pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Largest number of samples per pixel.
pub const MAX_SPP: u32 = 256;

/// What to render and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    pub camera: Camera,
    /// Image size, pixels.
    pub width: u32,
    pub height: u32,
    /// Rays per pixel (1 … 256), averaged in linear light.
    pub spp: u32,
    pub lighting: Lighting,
    /// Repeat the field to the horizon; `None`: when it is periodic.
    pub repeat: Option<bool>,
    /// Low-pass the surface by the rays' footprint (mean mip levels); off, every ray sees
    /// the full-resolution surface.
    pub lod: bool,
    /// Rays end here (they show the sky), meters.
    pub max_distance_m: f64,
    /// Water (sky reflection, sun glitter, whitecaps) or terrain (diffuse rock, grass, snow).
    pub material: Material,
}

/// How the surface is shaded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Material {
    /// The sea of [`shade`]: height color, spray, Fresnel sky reflection, sun glitter;
    /// foam coverage, when given, as whitecaps.
    #[default]
    Water,
    /// Land: albedo by height and slope (grass, rock, snow), lit diffusely by the sun and
    /// the sky; no reflection.
    Terrain,
}

/// Per-sample maps that go with a field, row-major like it.
#[derive(Debug, Clone, Copy, Default)]
pub struct Maps<'a> {
    /// Exact ∂h/∂x and ∂h/∂y (`None`: central differences).
    pub slopes: Option<(&'a [f32], &'a [f32])>,
    /// Foam coverage in [0, 1], drawn as whitecaps (`None`: no foam).
    pub foam: Option<&'a [f32]>,
}

/// A rendered image: 8-bit sRGB, rows top to bottom, and the distance to the sea seen
/// through each pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    /// `width`·`height`·3 bytes, R, G, B.
    pub rgb: Vec<u8>,
    /// Per pixel, the nearest hit among its rays, meters (infinite where every ray sees sky).
    pub distance_m: Vec<f32>,
}

impl RgbImage {
    /// The color of pixel (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let k = 3 * (y as usize * self.width as usize + x as usize);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }
}

fn err(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

impl RenderOptions {
    /// 1280×720, 4 rays per pixel, the default lighting, repeat when periodic, low-pass on.
    pub fn new(camera: Camera) -> Self {
        Self {
            camera,
            width: 1280,
            height: 720,
            spp: 4,
            lighting: Lighting::default(),
            repeat: None,
            lod: true,
            max_distance_m: f64::INFINITY,
            material: Material::Water,
        }
    }

    /// The default preview of `field`: the grazing view down-wind (`wind_dir_rad`, from
    /// +x toward +y) framed by its peak wavelength, the lighting of [`lighting_for`].
    pub fn preview(field: &Grid, wind_dir_rad: f64, periodic: bool) -> Self {
        let scene = scene_of(field, wind_dir_rad, periodic);
        let camera = View::Grazing.camera(&scene, 1280, 720, View::Grazing.fov_x_rad());
        let mut o = Self::new(camera);
        o.lighting = lighting_for(&scene, &camera);
        o
    }

    /// Checks every value; names the flag at fault.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.camera.validate()?;
        let sides = 1..=MAX_IMAGE_SIDE;
        if !(sides.contains(&self.width) && sides.contains(&self.height)) {
            return Err(err(
                "--image",
                &format!("WxH with each side from 1 to {MAX_IMAGE_SIDE} pixels"),
                format!("{}x{}", self.width, self.height),
            ));
        }
        if !(1..=MAX_SPP).contains(&self.spp) {
            return Err(err("--spp", &format!("from 1 to {MAX_SPP}"), self.spp));
        }
        let l = &self.lighting;
        if !l.sun_dir.iter().all(|v| v.is_finite()) {
            return Err(err("--sun", "a finite azimuth and elevation", "NaN"));
        }
        if l.haze_distance_m.is_nan() || l.haze_distance_m < 0.0 {
            return Err(err(
                "--haze",
                "a distance ≥ 0 m (0: no haze)",
                l.haze_distance_m,
            ));
        }
        match l.reflection {
            Reflection::Fresnel { index } if !(index.is_finite() && index >= 1.0) => {
                return Err(err("--reflection", "fresnel with an index ≥ 1", index));
            }
            Reflection::Pseudo { exponent } if !(exponent.is_finite() && exponent > 0.0) => {
                return Err(err(
                    "--reflection",
                    "pseudo:C with a finite C > 0",
                    exponent,
                ));
            }
            _ => {}
        }
        if self.max_distance_m.is_nan() || self.max_distance_m <= 0.0 {
            return Err(err("max distance", "> 0 m", self.max_distance_m));
        }
        Ok(())
    }
}

/// What the views need to know of `field`.
pub fn scene_of(field: &Grid, wind_dir_rad: f64, periodic: bool) -> Scene {
    let s = field.spec;
    let (cx, cy) = if periodic {
        (s.nx, s.ny)
    } else {
        (s.nx.saturating_sub(1), s.ny.saturating_sub(1))
    };
    let stats = field.stats();
    let size_m = [cx as f64 * s.dx_m(), cy as f64 * s.dy_m()];
    Scene {
        size_m,
        mean_m: stats.mean_m,
        max_m: stats.max_m,
        hs_m: stats.hs_m,
        wind_dir_rad,
        peak_wavelength_m: peak_wavelength_m(field, periodic),
    }
}

/// Largest side of the copy of a field whose spectrum gives its peak wavelength.
const PEAK_SIDE: usize = 512;

/// The wavelength of the peak of `field`'s measured omnidirectional spectrum S(k)
/// ([`crate::measure::spectrum`]), meters: the field block-averaged to at most
/// 512² samples (a low-pass that keeps the peak of any field whose peak
/// wavelength spans several blocks), with a Hann window when it is not periodic (its
/// edges would otherwise add power at the lowest wavenumbers). Kept between 8 sample
/// spacings and the field's size; the field's size for a flat field.
pub fn peak_wavelength_m(field: &Grid, periodic: bool) -> f64 {
    let s = field.spec;
    let size = s.extent_x_m.max(s.extent_y_m);
    let (bx, by) = (s.nx.div_ceil(PEAK_SIDE), s.ny.div_ceil(PEAK_SIDE));
    let (nx, ny) = (s.nx / bx, s.ny / by);
    if nx < 4 || ny < 4 {
        return size;
    }
    let spec = crate::grid::GridSpec::new(
        nx,
        ny,
        s.dx_m() * (nx * bx) as f64,
        s.dy_m() * (ny * by) as f64,
    );
    let mean = field.stats().mean_m;
    let hann = |i: usize, n: usize| {
        if periodic {
            1.0
        } else {
            (std::f64::consts::PI * (i as f64 + 0.5) / n as f64)
                .sin()
                .powi(2)
        }
    };
    let data: Vec<f32> = (0..nx * ny)
        .map(|k| {
            let (i, j) = (k % nx, k / nx);
            let mut sum = 0.0f64;
            for b in 0..by {
                let row = field.row(j * by + b);
                for a in 0..bx {
                    sum += row[i * bx + a] as f64 - mean;
                }
            }
            (sum / (bx * by) as f64 * hann(i, nx) * hann(j, ny)) as f32
        })
        .collect();
    let low = s.dx_m().max(s.dy_m()) * 8.0;
    crate::measure::spectrum::analyze(&Grid::new(spec, data), None)
        .peak_wavelength_m
        .filter(|l| l.is_finite())
        .map_or(size, |l| l.clamp(low.min(size), size))
}

/// The default lighting for a camera over `scene`: the sun 20° to the left of the look
/// direction and 14° up, so its glitter lies on the sea ahead; haze at 4 field sizes or
/// 10 camera heights, whichever is farther.
pub fn lighting_for(scene: &Scene, camera: &Camera) -> Lighting {
    let size = scene.size_m[0].max(scene.size_m[1]);
    let height = camera.position_m[2] - scene.mean_m;
    Lighting {
        sun_dir: shade::sun_direction(camera.yaw_rad + 20f64.to_radians(), 14f64.to_radians()),
        haze_distance_m: (4.0 * size).max(10.0 * height),
        ..Lighting::default()
    }
}

/// Sub-pixel offsets of `spp` rays, in [0, 1)²: a grid for a square number, else the
/// rows of an n-rooks pattern with a golden-ratio stride. Fixed, so images are repeatable.
pub fn sample_offsets(spp: u32) -> Vec<(f64, f64)> {
    let n = spp.max(1) as usize;
    let side = (n as f64).sqrt().round() as usize;
    if side * side == n {
        return (0..n)
            .map(|k| {
                (
                    ((k % side) as f64 + 0.5) / side as f64,
                    ((k / side) as f64 + 0.5) / side as f64,
                )
            })
            .collect();
    }
    let mut stride = ((n as f64) * 0.618_033_988_749_895).round().max(1.0) as usize;
    while gcd(stride, n) != 1 {
        stride += 1;
    }
    (0..n)
        .map(|k| {
            (
                (k as f64 + 0.5) / n as f64,
                ((k * stride % n) as f64 + 0.5) / n as f64,
            )
        })
        .collect()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// Renders `field` (heights in meters on its grid). `slopes`: exact ∂h/∂x and ∂h/∂y per
/// sample, row-major like the field (`None`: central differences). `periodic`: sample N
/// equals sample 0, so the field may repeat.
pub fn render(
    field: &Grid,
    slopes: Option<(&[f32], &[f32])>,
    periodic: bool,
    opts: &RenderOptions,
) -> Result<RgbImage, Error> {
    render_with_progress(field, slopes, periodic, opts, &|_| {})
}

/// [`render`], calling `progress(rows)` as rows of the image are done (from any thread).
pub fn render_with_progress(
    field: &Grid,
    slopes: Option<(&[f32], &[f32])>,
    periodic: bool,
    opts: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RgbImage, Error> {
    let maps = Maps { slopes, foam: None };
    render_maps(field, &maps, periodic, opts, progress)
}

/// [`render_with_progress`] with the field's [`Maps`]: exact slopes and foam coverage.
pub fn render_maps(
    field: &Grid,
    maps: &Maps,
    periodic: bool,
    opts: &RenderOptions,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RgbImage, Error> {
    let slopes = maps.slopes;
    opts.validate()?;
    let (nx, ny) = (field.spec.nx, field.spec.ny);
    if nx < 2 || ny < 2 {
        return Err(err(
            "the height field",
            "at least 2×2 samples",
            format!("{nx}×{ny}"),
        )
        .into());
    }
    let wrap = opts.repeat.unwrap_or(periodic);
    let owned;
    let (sx, sy) = match slopes {
        Some((sx, sy)) => {
            if sx.len() != nx * ny || sy.len() != nx * ny {
                return Err(err(
                    "the slope arrays",
                    &format!("{} values each, one per sample", nx * ny),
                    format!("{} and {}", sx.len(), sy.len()),
                )
                .into());
            }
            (sx, sy)
        }
        None => {
            owned = central_slopes(field, wrap);
            (owned.0.as_slice(), owned.1.as_slice())
        }
    };
    let pyr = Pyramid::new(field, sx, sy, wrap);
    check_above_surface(&pyr, &opts.camera)?;
    let foam = match maps.foam {
        Some(f) if f.len() != nx * ny => {
            return Err(err(
                "the foam coverage",
                &format!("{} values, one per sample", nx * ny),
                f.len(),
            )
            .into());
        }
        // The coverage as a surface of its own: its mean levels low-pass it like the
        // heights, by the ray's footprint.
        Some(f) if opts.material == Material::Water && f.iter().any(|&v| v > 0.0) => {
            let zero = vec![0.0f32; nx * ny];
            Some(Pyramid::new(
                &Grid::new(field.spec, f.to_vec()),
                &zero,
                &zero,
                wrap,
            ))
        }
        _ => None,
    };
    let cell_w = (pyr.dx_m * pyr.dy_m).sqrt();
    let stats = field.stats();
    let scale = HeightScale {
        mean_m: stats.mean_m,
        amplitude_m: (stats.max_m - stats.mean_m).max(stats.mean_m - stats.min_m),
    };
    let proj = Projection::new(&opts.camera, opts.width, opts.height);
    let offsets = sample_offsets(opts.spp);
    let lod = Lod {
        angle_rad: if opts.lod {
            proj.pixel_angle_rad() / (opts.spp as f64).sqrt()
        } else {
            0.0
        },
    };
    let mut tracer = Tracer::new(&pyr, lod);
    tracer.max_distance_m = opts.max_distance_m;
    let (w, h) = (opts.width as usize, opts.height as usize);
    let mut rgb = vec![0u8; w * h * 3];
    let mut distance_m = vec![f32::INFINITY; w * h];
    let light = &opts.lighting;
    let inv = 1.0 / offsets.len() as f64;
    rgb.par_chunks_mut(w * 3)
        .zip(distance_m.par_chunks_mut(w))
        .enumerate()
        .for_each(|(y, (row, dist))| {
            for x in 0..w {
                let mut acc = [0.0f64; 3];
                let mut nearest = f64::INFINITY;
                for &(ox, oy) in &offsets {
                    let dir = proj.direction(x as f64 + ox, y as f64 + oy);
                    let ray = Ray {
                        origin: proj.origin(),
                        dir,
                    };
                    let c = match tracer.trace(&ray) {
                        Some(hit) => {
                            nearest = nearest.min(hit.t);
                            match opts.material {
                                Material::Water => {
                                    let cover = foam.as_ref().map_or(0.0, |f| {
                                        let level =
                                            footprint_level(lod.angle_rad, dir, hit.t, cell_w);
                                        foam_at(f, hit.point, level)
                                    });
                                    light.sea_with_foam(
                                        dir,
                                        hit.t,
                                        hit.height_m,
                                        hit.normal(),
                                        &scale,
                                        cover,
                                    )
                                }
                                Material::Terrain => {
                                    light.terrain(dir, hit.t, hit.height_m, hit.normal(), &scale)
                                }
                            }
                        }
                        None => light.background(dir),
                    };
                    for k in 0..3 {
                        acc[k] += c[k];
                    }
                }
                for k in 0..3 {
                    row[3 * x + k] = shade::encode_srgb8(acc[k] * inv);
                }
                dist[x] = nearest as f32;
            }
            progress(1);
        });
    Ok(RgbImage {
        width: opts.width,
        height: opts.height,
        rgb,
        distance_m,
    })
}

/// The mean level λ = log2(w/cell) a ray along `dir` sees at distance `t_m`, w its
/// footprint (as the tracer computes it; 0 without the low-pass).
fn footprint_level(angle_rad: f64, dir: [f64; 3], t_m: f64, cell_m: f64) -> f64 {
    let w = angle_rad / dir[2].abs().max(0.01).sqrt() / cell_m * t_m;
    if w > 1.0 { w.log2() } else { 0.0 }
}

/// Foam coverage at (x, y) on mean level λ (blended between ⌊λ⌋ and ⌊λ⌋ + 1), in [0, 1].
fn foam_at(f: &Pyramid, p: [f64; 3], level: f64) -> f64 {
    let l = level.floor();
    let frac = level - l;
    let l = l as usize;
    let a = f.surface(l, p[0], p[1])[0];
    let c = if frac > 0.0 {
        a + (f.surface(l + 1, p[0], p[1])[0] - a) * frac
    } else {
        a
    };
    c.clamp(0.0, 1.0)
}

/// The height of the surface the tracer sees under (x, y): the field, its repeats, or the
/// mean plane around a field that does not repeat.
fn surface_under(pyr: &Pyramid, x: f64, y: f64) -> f64 {
    let inside = |v: f64, cells: usize, d: f64| (0.0..=cells as f64 * d).contains(&v);
    if pyr.wrap || (inside(x, pyr.cells_x, pyr.dx_m) && inside(y, pyr.cells_y, pyr.dy_m)) {
        pyr.surface(0, x, y)[0]
    } else {
        pyr.mean_m
    }
}

fn check_above_surface(pyr: &Pyramid, camera: &Camera) -> Result<(), ParamError> {
    let [x, y, z] = camera.position_m;
    let s = surface_under(pyr, x, y);
    if z > s {
        Ok(())
    } else {
        Err(err(
            "--camera",
            &format!("above the sea surface, which is at z = {s:.3} m under x = {x} m, y = {y} m"),
            format!("z = {z:.3} m"),
        ))
    }
}

#[cfg(test)]
mod tests;
