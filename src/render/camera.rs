//! The pinhole camera and the named views.
//!
//! Conventions: world x and y are the field's axes (meters, as in [`crate::grid`]), z is up
//! (heights in meters, the same values as the field). Yaw is the compass of the look
//! direction measured like the wind direction, from +x toward +y; pitch is the angle above
//! the horizontal (negative: looking down). The image's right is the look direction turned
//! 90° clockwise seen from above (looking along +x, +y is to the left), its up is the
//! world's up tilted with the pitch; looking straight down, the image's up is the yaw.
//! The field of view is horizontal; the vertical one follows from the image's aspect.

use crate::error::ParamError;

/// A pinhole camera (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Position, meters.
    pub position_m: [f64; 3],
    /// Look direction from +x toward +y, radians.
    pub yaw_rad: f64,
    /// Look direction above the horizontal, radians, in [−π/2, π/2].
    pub pitch_rad: f64,
    /// Horizontal field of view, radians, in (0, π).
    pub fov_x_rad: f64,
}

fn err(name: &str, allowed: &str, got: impl std::fmt::Display) -> ParamError {
    ParamError {
        name: name.to_string(),
        allowed: allowed.to_string(),
        got: got.to_string(),
    }
}

/// Shows a triple as the user writes it.
pub fn triple(v: [f64; 3]) -> String {
    format!("{},{},{}", v[0], v[1], v[2])
}

impl Camera {
    /// Checks every value: finite position, pitch within ±90°, 0 < fov < 180°.
    pub fn validate(&self) -> Result<(), ParamError> {
        if !self.position_m.iter().all(|v| v.is_finite()) {
            return Err(err(
                "--camera",
                "three finite numbers X,Y,Z in meters",
                triple(self.position_m),
            ));
        }
        if !self.yaw_rad.is_finite() {
            return Err(err(
                "--yaw",
                "a finite angle in degrees",
                self.yaw_rad.to_degrees(),
            ));
        }
        let half_pi = std::f64::consts::FRAC_PI_2;
        if !(self.pitch_rad.is_finite() && self.pitch_rad.abs() <= half_pi + 1e-12) {
            return Err(err(
                "--pitch",
                "an angle from -90° to 90°",
                self.pitch_rad.to_degrees(),
            ));
        }
        let fov = self.fov_x_rad;
        if !(fov.is_finite() && fov > 0.0 && fov < std::f64::consts::PI) {
            return Err(err("--fov", "an angle > 0° and < 180°", fov.to_degrees()));
        }
        Ok(())
    }

    /// Yaw and pitch that look from `from` toward `to` (radians).
    pub fn aim(from: [f64; 3], to: [f64; 3]) -> Result<(f64, f64), ParamError> {
        let d = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
        let horizontal = d[0].hypot(d[1]);
        if !(horizontal > 0.0 || d[2] != 0.0) || !d.iter().all(|v| v.is_finite()) {
            return Err(err(
                "--look-at",
                "a finite point other than the camera's position",
                triple(to),
            ));
        }
        let yaw = if horizontal > 0.0 {
            d[1].atan2(d[0])
        } else {
            0.0
        };
        Ok((yaw, d[2].atan2(horizontal)))
    }

    /// The orthonormal frame (forward, right, up).
    pub fn frame(&self) -> [[f64; 3]; 3] {
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sp, cp) = self.pitch_rad.sin_cos();
        let forward = [cp * cy, cp * sy, sp];
        let right = [sy, -cy, 0.0];
        // up = right × forward
        let up = [
            right[1] * forward[2] - right[2] * forward[1],
            right[2] * forward[0] - right[0] * forward[2],
            right[0] * forward[1] - right[1] * forward[0],
        ];
        [forward, right, up]
    }
}

/// Rays through the pixels of a `width` × `height` image.
#[derive(Debug, Clone, Copy)]
pub struct Projection {
    origin: [f64; 3],
    frame: [[f64; 3]; 3],
    tan_x: f64,
    tan_y: f64,
    width: f64,
    height: f64,
}

impl Projection {
    pub fn new(camera: &Camera, width: u32, height: u32) -> Self {
        let tan_x = (camera.fov_x_rad / 2.0).tan();
        Self {
            origin: camera.position_m,
            frame: camera.frame(),
            tan_x,
            tan_y: tan_x * height as f64 / width as f64,
            width: width as f64,
            height: height as f64,
        }
    }

    /// The focal length in pixels: a ray `p` pixels from the center makes the angle
    /// atan(p/focal) with the axis.
    pub fn focal_px(&self) -> f64 {
        self.width / (2.0 * self.tan_x)
    }

    /// Angle between neighbouring pixels at the image's center, radians.
    pub fn pixel_angle_rad(&self) -> f64 {
        1.0 / self.focal_px()
    }

    /// Unit direction through image point (x, y) in pixels, (0, 0) the top left corner
    /// of the image and (width, height) its bottom right one.
    #[inline]
    pub fn direction(&self, x: f64, y: f64) -> [f64; 3] {
        let a = (2.0 * x / self.width - 1.0) * self.tan_x;
        let b = (1.0 - 2.0 * y / self.height) * self.tan_y;
        let [f, r, u] = self.frame;
        let d = [0, 1, 2].map(|k| f[k] + a * r[k] + b * u[k]);
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        d.map(|c| c / n)
    }

    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }
}

/// The named camera placements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Low over the sea at the upwind edge of the field, looking down-wind 7° down, the
    /// horizon in the upper third, 0.12 peak wavelengths above the mean (the default).
    Grazing,
    /// Above the upwind side, 4 peak wavelengths (at most 0.45 field sizes) from the
    /// center, looking down-wind at it 30° below the horizontal.
    Aerial,
    /// Straight down over the field's center, +x right and +y up, high enough to see
    /// the whole field.
    Top,
}

/// Names of the views, for the command line.
pub const VIEWS: &[(&str, View)] = &[
    ("grazing", View::Grazing),
    ("aerial", View::Aerial),
    ("top", View::Top),
];

/// What a view needs to know of the field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// Size of the field's surface (x, y), meters: nx·dx for a periodic field, (nx − 1)·dx
    /// otherwise; the field starts at (0, 0).
    pub size_m: [f64; 2],
    pub mean_m: f64,
    pub max_m: f64,
    /// Significant wave height 4·std, meters.
    pub hs_m: f64,
    /// Direction the wind blows toward, from +x toward +y, radians.
    pub wind_dir_rad: f64,
    /// The dominant wavelength λp (the peak of the measured spectrum), meters: the scale
    /// the grazing and aerial views are framed by.
    pub peak_wavelength_m: f64,
}

/// Grazing view: camera height above the mean, in peak wavelengths (the image's center
/// ray, 7° down, meets the sea 8.1 such heights ahead: about one λp).
pub const GRAZING_HEIGHT_PER_WAVELENGTH: f64 = 0.12;
/// Aerial view: distance to the point looked at, in peak wavelengths (at most 0.45 field
/// sizes).
pub const AERIAL_DISTANCE_PER_WAVELENGTH: f64 = 4.0;

impl View {
    pub fn from_name(name: &str) -> Result<View, ParamError> {
        VIEWS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| *v)
            .ok_or_else(|| {
                let names: Vec<&str> = VIEWS.iter().map(|(n, _)| *n).collect();
                err("--view", &format!("one of {}", names.join(", ")), name)
            })
    }

    /// Default horizontal field of view, radians.
    pub fn fov_x_rad(self) -> f64 {
        match self {
            View::Grazing | View::Aerial => 60f64.to_radians(),
            View::Top => 50f64.to_radians(),
        }
    }

    /// The camera of this view for `scene`, with a `width` × `height` image and a
    /// horizontal field of view `fov_x_rad` (the top view rises to fit the field in it).
    pub fn camera(self, scene: &Scene, width: u32, height: u32, fov_x_rad: f64) -> Camera {
        let [lx, ly] = scene.size_m;
        let center = [lx / 2.0, ly / 2.0];
        let (ws, wc) = scene.wind_dir_rad.sin_cos();
        // Distance from the center to the field's edge along the wind.
        let reach = (if wc != 0.0 {
            lx / 2.0 / wc.abs()
        } else {
            f64::INFINITY
        })
        .min(if ws != 0.0 {
            ly / 2.0 / ws.abs()
        } else {
            f64::INFINITY
        });
        let size = lx.max(ly);
        let fov_x = fov_x_rad;
        match self {
            View::Grazing => {
                // Framed by λp: the sea ahead is the same number of wavelengths whatever
                // its scale, so its steepness shows. The center ray meets the mean
                // 8.1 heights ahead: inside a field that does not repeat, it stays within
                // 90 % of the field's length along the wind (2·reach).
                let tan_pitch = 7f64.to_radians().tan();
                let mut above = GRAZING_HEIGHT_PER_WAVELENGTH * scene.peak_wavelength_m;
                if reach.is_finite() {
                    above = above.min(0.9 * 2.0 * reach * tan_pitch);
                }
                let above = above.max(1e-3 * size);
                Camera {
                    position_m: [
                        center[0] - wc * reach,
                        center[1] - ws * reach,
                        (scene.mean_m + above).max(scene.max_m + 0.1 * scene.hs_m + 0.1),
                    ],
                    yaw_rad: scene.wind_dir_rad,
                    pitch_rad: -(7f64.to_radians()),
                    fov_x_rad: fov_x,
                }
            }
            View::Aerial => {
                let pitch = 30f64.to_radians();
                let distance =
                    (AERIAL_DISTANCE_PER_WAVELENGTH * scene.peak_wavelength_m).min(0.45 * size);
                Camera {
                    position_m: [
                        center[0] - wc * distance * pitch.cos(),
                        center[1] - ws * distance * pitch.cos(),
                        scene.mean_m + distance * pitch.sin(),
                    ],
                    yaw_rad: scene.wind_dir_rad,
                    pitch_rad: -pitch,
                    fov_x_rad: fov_x,
                }
            }
            View::Top => {
                let tan_x = (fov_x / 2.0).tan();
                let tan_y = tan_x * height as f64 / width as f64;
                let above = (lx / 2.0 / tan_x).max(ly / 2.0 / tan_y);
                Camera {
                    position_m: [center[0], center[1], scene.max_m + above],
                    yaw_rad: std::f64::consts::FRAC_PI_2,
                    pitch_rad: -std::f64::consts::FRAC_PI_2,
                    fov_x_rad: fov_x,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ANGLE_TOL: f64 = 1e-12;

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn the_frame_is_orthonormal_and_right_handed() {
        for (yaw, pitch) in [
            (0.0, 0.0),
            (1.0, -0.3),
            (-2.0, 1.2),
            (0.4, -std::f64::consts::FRAC_PI_2),
        ] {
            let c = Camera {
                position_m: [0.0; 3],
                yaw_rad: yaw,
                pitch_rad: pitch,
                fov_x_rad: 1.0,
            };
            let [f, r, u] = c.frame();
            for (a, b) in [(f, r), (f, u), (r, u)] {
                assert!(
                    dot(a, b).abs() < ANGLE_TOL,
                    "yaw {yaw}, pitch {pitch}: not orthogonal"
                );
            }
            for v in [f, r, u] {
                assert!((dot(v, v) - 1.0).abs() < ANGLE_TOL);
            }
            assert!(u[2] >= 0.0, "up points up");
        }
        // Looking along +x, +y is on the left: right = −y.
        let c = Camera {
            position_m: [0.0; 3],
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            fov_x_rad: 1.0,
        };
        assert_eq!(c.frame()[1], [0.0, -1.0, 0.0]);
    }

    #[test]
    fn pixels_at_the_image_edge_are_half_the_field_of_view_off_axis() {
        let c = Camera {
            position_m: [0.0; 3],
            yaw_rad: 0.3,
            pitch_rad: -0.2,
            fov_x_rad: 90f64.to_radians(),
        };
        let p = Projection::new(&c, 200, 100);
        let axis = p.direction(100.0, 50.0);
        assert!((dot(axis, c.frame()[0]) - 1.0).abs() < ANGLE_TOL);
        let edge = p.direction(200.0, 50.0);
        assert!((dot(edge, axis) - 45f64.to_radians().cos()).abs() < ANGLE_TOL);
        // Square pixels: the top edge is atan(tan 45° · 100/200) above the axis.
        let top = p.direction(100.0, 0.0);
        assert!((dot(top, axis) - 0.5f64.atan().cos()).abs() < ANGLE_TOL);
        assert!(
            dot(top, c.frame()[2]) > 0.0,
            "row 0 is the top of the image"
        );
    }

    #[test]
    fn aim_and_validation() {
        let (yaw, pitch) = Camera::aim([0.0, 0.0, 10.0], [10.0, 10.0, 0.0]).unwrap();
        assert!((yaw - 45f64.to_radians()).abs() < ANGLE_TOL);
        assert!((pitch + (10.0 / 200f64.sqrt()).atan()).abs() < ANGLE_TOL);
        assert!(Camera::aim([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]).is_err());
        let good = Camera {
            position_m: [0.0, 0.0, 5.0],
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            fov_x_rad: 1.0,
        };
        assert!(good.validate().is_ok());
        for (bad, name) in [
            (
                Camera {
                    fov_x_rad: 0.0,
                    ..good
                },
                "--fov",
            ),
            (
                Camera {
                    fov_x_rad: std::f64::consts::PI,
                    ..good
                },
                "--fov",
            ),
            (
                Camera {
                    fov_x_rad: f64::NAN,
                    ..good
                },
                "--fov",
            ),
            (
                Camera {
                    pitch_rad: 2.0,
                    ..good
                },
                "--pitch",
            ),
            (
                Camera {
                    position_m: [0.0, f64::NAN, 1.0],
                    ..good
                },
                "--camera",
            ),
        ] {
            let e = bad.validate().unwrap_err();
            assert_eq!(e.name, name, "{e}");
        }
    }

    #[test]
    fn every_view_looks_at_the_field() {
        let scene = Scene {
            size_m: [512.0, 256.0],
            mean_m: 0.0,
            max_m: 2.0,
            hs_m: 1.2,
            wind_dir_rad: 30f64.to_radians(),
            peak_wavelength_m: 40.0,
        };
        for (name, view) in VIEWS {
            let c = view.camera(&scene, 640, 360, view.fov_x_rad());
            c.validate().unwrap();
            // The ray through the image's center comes down inside the field.
            let [f, ..] = c.frame();
            assert!(f[2] < 0.0, "{name} looks down");
            let t = (c.position_m[2] - scene.mean_m) / -f[2];
            let (x, y) = (c.position_m[0] + f[0] * t, c.position_m[1] + f[1] * t);
            assert!(
                (0.0..=512.0).contains(&x) && (0.0..=256.0).contains(&y),
                "{name}: the center ray meets the sea at ({x}, {y})"
            );
            assert!(c.position_m[2] > scene.max_m, "{name}: above the crests");
        }
    }

    /// The grazing and aerial views scale with the peak wavelength, not with Hs: a sea
    /// 40 times larger (sizes, heights and λp) is seen from 40 times as far, and a
    /// steeper sea of the same λp from the same place.
    #[test]
    fn views_are_framed_by_the_peak_wavelength() {
        let small = Scene {
            size_m: [256.0, 256.0],
            mean_m: 0.0,
            max_m: 0.4,
            hs_m: 0.4,
            wind_dir_rad: 0.0,
            peak_wavelength_m: 13.0,
        };
        let big = Scene {
            size_m: small.size_m.map(|v| 40.0 * v),
            max_m: 40.0 * small.max_m,
            hs_m: 40.0 * small.hs_m,
            peak_wavelength_m: 40.0 * small.peak_wavelength_m,
            ..small
        };
        let steep = Scene {
            max_m: 1.0,
            hs_m: 1.0,
            ..small
        };
        for view in [View::Grazing, View::Aerial] {
            let a = view.camera(&small, 640, 360, view.fov_x_rad());
            let b = view.camera(&big, 640, 360, view.fov_x_rad());
            let c = view.camera(&steep, 640, 360, view.fov_x_rad());
            for k in 0..3 {
                assert!((b.position_m[k] - 40.0 * a.position_m[k]).abs() < 1e-9 * b.position_m[2]);
            }
            assert_eq!(
                a.position_m, c.position_m,
                "{view:?}: Hs does not move the camera"
            );
        }
        let g = View::Grazing.camera(&small, 640, 360, 1.0);
        assert!((g.position_m[2] - GRAZING_HEIGHT_PER_WAVELENGTH * 13.0).abs() < 1e-12);
    }
}
