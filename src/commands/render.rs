//! `seasynth render`: the command line turned into a field and [`RenderOptions`], the
//! image rendered with a progress bar and written through a staged file.

use std::time::Instant;

use anyhow::Result;

use crate::cli::RenderArgs;
use crate::config::Params;
use crate::error::{Error, ParamError};
use crate::export::{Allowed, Staged};
use crate::grid::Grid;
use crate::render::camera::{Camera, View, triple};
use crate::render::shade::{PSEUDO_EXPONENT, Reflection, WATER_INDEX, sun_direction};
use crate::render::{
    MAX_IMAGE_SIDE, MAX_SPP, Maps, Material, RenderOptions, lighting_for, scene_of,
};

/// Renders with fewer rays than this show no progress bar.
const PROGRESS_MIN_RAYS: u64 = 1 << 20;

fn err(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

/// A number of `flag`; `allowed` says what the flag takes, for the error.
fn number(flag: &str, allowed: &str, s: &str) -> Result<f64, ParamError> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| err(flag, allowed, s))
}

/// `N` finite numbers separated by commas.
fn numbers<const N: usize>(flag: &str, allowed: &str, s: &str) -> Result<[f64; N], ParamError> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != N {
        return Err(err(flag, allowed, s));
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = number(flag, allowed, p).map_err(|_| err(flag, allowed, s))?;
    }
    Ok(out)
}

/// `WxH` in pixels.
fn image_size(s: &str) -> Result<(u32, u32), ParamError> {
    let allowed = format!("WxH with each side from 1 to {MAX_IMAGE_SIDE} pixels");
    let bad = || err("--image", &allowed, s);
    let (w, h) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let side = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_IMAGE_SIDE).contains(v))
    };
    Ok((side(w).ok_or_else(bad)?, side(h).ok_or_else(bad)?))
}

/// The render flags, parsed and checked before any work.
struct Request {
    width: u32,
    height: u32,
    spp: u32,
    view: View,
    position: Option<[f64; 3]>,
    camera_height: Option<f64>,
    yaw_rad: Option<f64>,
    pitch_rad: Option<f64>,
    look_at: Option<[f64; 3]>,
    fov_x_rad: Option<f64>,
    sun: Option<[f64; 2]>,
    haze_m: Option<f64>,
    reflection: Option<Reflection>,
    repeat: Option<bool>,
    lod: bool,
}

impl Request {
    fn parse(a: &RenderArgs) -> Result<Request, ParamError> {
        let (width, height) = match &a.image {
            Some(s) => image_size(s)?,
            None => (1280, 720),
        };
        let spp = match &a.spp {
            Some(s) => s
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|v| (1..=MAX_SPP).contains(v))
                .ok_or_else(|| err("--spp", &format!("a whole number from 1 to {MAX_SPP}"), s))?,
            None => 4,
        };
        let view = match &a.view {
            Some(s) => View::from_name(s)?,
            None => View::Grazing,
        };
        let point = "three finite numbers X,Y,Z in meters";
        let position = a
            .camera
            .as_deref()
            .map(|s| numbers::<3>("--camera", point, s))
            .transpose()?;
        let camera_height = a
            .camera_height
            .as_deref()
            .map(|s| number("--camera-height", "a finite number of meters", s))
            .transpose()?;
        let angle = |flag: &str, s: &Option<String>, lo: f64, hi: f64| {
            let allowed = format!("an angle from {lo}° to {hi}°");
            s.as_deref()
                .map(|s| {
                    number(flag, &allowed, s).and_then(|v| {
                        (lo..=hi)
                            .contains(&v)
                            .then_some(v.to_radians())
                            .ok_or_else(|| err(flag, &allowed, s))
                    })
                })
                .transpose()
        };
        let yaw_rad = angle("--yaw", &a.yaw, -360.0, 360.0)?;
        let pitch_rad = angle("--pitch", &a.pitch, -90.0, 90.0)?;
        let look_at = a
            .look_at
            .as_deref()
            .map(|s| numbers::<3>("--look-at", point, s))
            .transpose()?;
        if let Some(p) = look_at {
            if yaw_rad.is_some() || pitch_rad.is_some() {
                return Err(err(
                    "--look-at",
                    "given without --yaw and --pitch",
                    triple(p),
                ));
            }
        }
        let fov_x_rad = match &a.fov {
            Some(s) => {
                let allowed = "an angle > 0° and < 180°";
                let v = number("--fov", allowed, s)?;
                if !(v > 0.0 && v < 180.0) {
                    return Err(err("--fov", allowed, s));
                }
                Some(v.to_radians())
            }
            None => None,
        };
        let sun = match &a.sun {
            Some(s) => {
                let allowed = "AZ,EL in degrees, the elevation from -90 to 90";
                let [az, el] = numbers::<2>("--sun", allowed, s)?;
                if !(-90.0..=90.0).contains(&el) {
                    return Err(err("--sun", allowed, s));
                }
                Some([az.to_radians(), el.to_radians()])
            }
            None => None,
        };
        let haze_m = match &a.haze {
            Some(s) => {
                let allowed = "a distance ≥ 0 m (0: no haze)";
                let v = number("--haze", allowed, s)?;
                if v < 0.0 {
                    return Err(err("--haze", allowed, s));
                }
                Some(v)
            }
            None => None,
        };
        let reflection = a.reflection.as_deref().map(parse_reflection).transpose()?;
        let repeat = if a.repeat {
            Some(true)
        } else if a.no_repeat {
            Some(false)
        } else {
            None
        };
        Ok(Request {
            width,
            height,
            spp,
            view,
            position,
            camera_height,
            yaw_rad,
            pitch_rad,
            look_at,
            fov_x_rad,
            sun,
            haze_m,
            reflection,
            repeat,
            lod: !a.no_lod,
        })
    }

    /// The camera: the view's, then the flags over it.
    fn camera(&self, scene: &crate::render::Scene) -> Result<Camera, ParamError> {
        let fov = self.fov_x_rad.unwrap_or(self.view.fov_x_rad());
        let mut c = self.view.camera(scene, self.width, self.height, fov);
        if let Some(p) = self.position {
            c.position_m = p;
        }
        if let Some(h) = self.camera_height {
            c.position_m[2] = scene.mean_m + h;
        }
        if let Some(target) = self.look_at {
            (c.yaw_rad, c.pitch_rad) = Camera::aim(c.position_m, target)?;
        }
        if let Some(y) = self.yaw_rad {
            c.yaw_rad = y;
        }
        if let Some(p) = self.pitch_rad {
            c.pitch_rad = p;
        }
        c.validate()?;
        Ok(c)
    }
}

fn parse_reflection(s: &str) -> Result<Reflection, ParamError> {
    let allowed = "fresnel, pseudo or pseudo:C with C > 0";
    match s.split_once(':') {
        None if s == "fresnel" => Ok(Reflection::Fresnel { index: WATER_INDEX }),
        None if s == "pseudo" => Ok(Reflection::Pseudo {
            exponent: PSEUDO_EXPONENT,
        }),
        Some(("pseudo", c)) => {
            let exponent = number("--reflection", allowed, c)?;
            if exponent > 0.0 {
                Ok(Reflection::Pseudo { exponent })
            } else {
                Err(err("--reflection", allowed, s))
            }
        }
        _ => Err(err("--reflection", allowed, s)),
    }
}

/// The field to render: read (`--from`) or synthesized, its wind direction (radians),
/// whether it is periodic, its material and its foam coverage (synthesized choppy fields).
struct Field {
    grid: Grid,
    wind_dir_rad: f64,
    periodic: bool,
    material: Material,
    foam: Option<Vec<f32>>,
}

fn field(args: &RenderArgs) -> Result<Field, Error> {
    let Some(from) = &args.from else {
        let params = crate::commands::common::resolve_params(&args.field)?;
        let [nx, ny] = params.grid.size.0;
        crate::limits::check_memory(
            footprint(&params).bytes(params.grid_spec().len() as u64, 1),
            &format!("rendering a {nx}x{ny} {} field", params.method.name()),
            args.field.force,
        )?;
        let extras = crate::pipeline::preview::preview_extras(&params);
        let synthesis =
            crate::field::Synthesizer::new(&params, extras, false)?.frame(params.time_s);
        crate::limits::check_finite(&synthesis.grid.stats(), "the synthesized field")?;
        let foam = crate::pipeline::preview::foam_coverage(&synthesis, &params);
        return Ok(Field {
            grid: synthesis.grid,
            wind_dir_rad: params.wind.direction_deg.to_radians(),
            periodic: crate::field::method_for(&params).is_periodic(),
            material: crate::pipeline::preview::material_of(&params),
            foam,
        });
    };
    let f = &args.field;
    if let Some(flag) = f
        .preset
        .as_ref()
        .map(|_| "--preset")
        .or((!f.set.is_empty()).then_some("--set"))
        .or(f
            .flags()
            .into_iter()
            .map(|(k, _)| k)
            .find(|k| !FROM_FLAGS.contains(k)))
    {
        return Err(err(
            "--from",
            "given without field flags but --extent and --height-range (the file is the field)",
            format!("{} with {flag}", from.display()),
        )
        .into());
    }
    let (grid, sidecar) = read_from(from, f)?;
    let params: Option<Params> = sidecar
        .as_ref()
        .and_then(|d| d.get("params"))
        .and_then(|v| serde_json::from_value(v.clone()).ok());
    Ok(match params {
        Some(p) => Field {
            grid,
            wind_dir_rad: p.wind.direction_deg.to_radians(),
            periodic: crate::field::method_for(&p).is_periodic(),
            material: crate::pipeline::preview::material_of(&p),
            foam: None,
        },
        None => Field {
            grid,
            wind_dir_rad: 0.0,
            periodic: false,
            material: Material::Water,
            foam: None,
        },
    })
}

/// The field flags that describe a `--from` file rather than a field.
const FROM_FLAGS: [&str; 2] = ["extent", "height-range"];

/// The height map of `--from`: any image read, with `--height-range` for integer images
/// without a mapping and `--extent` for the spacing.
fn read_from(
    from: &std::path::Path,
    f: &crate::cli::FieldArgs,
) -> Result<(Grid, Option<serde_json::Value>), Error> {
    let opts = crate::io::ReadOptions::parse(f.height_range.as_deref(), f.extent.as_deref())?;
    crate::io::load_with(from, &opts).map(|l| (l.grid, l.sidecar))
}

/// The files `render -o` writes.
const PREVIEWS: Allowed = Allowed {
    what: "previews are 8-bit RGB PNG, JPEG or WebP images",
    extensions: &["png", "jpg", "jpeg", "webp"],
};

/// Runs `seasynth render`.
pub fn run(args: RenderArgs) -> Result<()> {
    crate::commands::common::set_threads(args.threads)?;
    let req = Request::parse(&args).map_err(Error::from)?;
    if args.from.is_none() {
        crate::commands::common::refuse_no_effect("render", &args.field)?;
    }
    // The output is staged before any work: a bad path fails now, and an error later
    // leaves no partial file.
    let staged = Staged::create_checked(&args.output, &PREVIEWS, &[])?;
    let Field {
        grid,
        wind_dir_rad,
        periodic,
        material,
        foam,
    } = field(&args)?;
    let wrap = req.repeat.unwrap_or(periodic);
    let scene = scene_of(&grid, wind_dir_rad, wrap);
    let camera = req.camera(&scene).map_err(Error::from)?;
    let mut lighting = lighting_for(&scene, &camera);
    if let Some([az, el]) = req.sun {
        lighting.sun_dir = sun_direction(az, el);
    }
    if let Some(h) = req.haze_m {
        lighting.haze_distance_m = if h == 0.0 { f64::INFINITY } else { h };
    }
    if let Some(r) = req.reflection {
        lighting.reflection = r;
    }
    let opts = RenderOptions {
        width: req.width,
        height: req.height,
        spp: req.spp,
        lighting,
        repeat: req.repeat,
        lod: req.lod,
        material,
        ..RenderOptions::new(camera)
    };
    let rays = req.width as u64 * req.height as u64 * req.spp as u64;
    let bar = crate::pipeline::jobs::progress_bar(
        req.height as u64,
        "rendering {bar:40} {pos}/{len} rows, {eta} left",
        !args.quiet && rays >= PROGRESS_MIN_RAYS,
    );
    let start = Instant::now();
    let maps = Maps {
        slopes: None,
        foam: foam.as_deref(),
    };
    let image = crate::render::render_maps(&grid, &maps, periodic, &opts, &|n| bar.inc(n))?;
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    crate::export::rgb8::write_by_name(staged, &image.rgb, (image.width, image.height))?;
    if !args.quiet {
        let [x, y, z] = camera.position_m;
        eprintln!(
            "rendered {}×{} at {} rays per pixel in {seconds:.2} s ({:.2} M rays/s); camera at ({x:.1}, {y:.1}, {z:.1}) m, yaw {:.1}°, pitch {:.1}°, fov {:.1}°{}",
            image.width,
            image.height,
            req.spp,
            rays as f64 / seconds / 1e6,
            camera.yaw_rad.to_degrees(),
            camera.pitch_rad.to_degrees(),
            camera.fov_x_rad.to_degrees(),
            if wrap { ", field repeated" } else { "" },
        );
        eprintln!("wrote {}", args.output.display());
    }
    Ok(())
}

/// Peak memory of rendering a synthesized field of `params`: the larger of the synthesis
/// and the render's own buffers (the field, its slopes, the mean and max pyramids:
/// 35 bytes a sample measured, 44 counted).
fn footprint(params: &crate::config::Params) -> crate::pipeline::memory::Footprint {
    let synthesis = crate::pipeline::memory::Footprint::of_field(params, Default::default());
    crate::pipeline::memory::Footprint {
        per_sample: synthesis.per_sample.max(44),
        ..synthesis
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Method;

    #[test]
    fn sizes_and_lists_parse_or_name_the_flag() {
        assert_eq!(image_size("640x360"), Ok((640, 360)));
        assert_eq!(image_size("64×36"), Ok((64, 36)));
        for bad in ["0x0", "640", "x", "640x-1", "99999x10"] {
            assert_eq!(image_size(bad).unwrap_err().name, "--image", "{bad}");
        }
        assert_eq!(
            numbers::<3>("--camera", "", "1,-2,3.5"),
            Ok([1.0, -2.0, 3.5])
        );
        assert!(numbers::<3>("--camera", "", "1,2").is_err());
        assert!(numbers::<3>("--camera", "", "1,nan,2").is_err());
        assert_eq!(
            parse_reflection("pseudo:0.5"),
            Ok(Reflection::Pseudo { exponent: 0.5 })
        );
        assert!(parse_reflection("pseudo:-1").is_err());
        assert!(parse_reflection("mirror").is_err());
    }

    #[test]
    fn periodic_methods_are_recognized() {
        let mut p = Params::default();
        assert!(
            !crate::field::method_for(&p).is_periodic(),
            "the default hybrid ramps α along y"
        );
        p.method = Method::Fft;
        assert!(crate::field::method_for(&p).is_periodic());
        p.method = Method::Perlin;
        p.perlin.tileable = false;
        assert!(!crate::field::method_for(&p).is_periodic());
    }
}
