//! Lighting, after Li, He & Gong (2015) §4, with a Fresnel term for the reflection.
//!
//! A point of the sea at height h with unit normal n, seen along the unit direction d
//! (from the camera; v = −d toward it), gets its color in steps, each a mix
//! c ← (1 − w)·c + w·color:
//! 1. **Height color**: h is mapped to [−1, 1] by the field's mean and largest deviation,
//!    then interpolates deep blue (0.02, 0.05, 0.10) → light green (0.0, 0.64, 0.68).
//! 2. **Spray** near the crests: w rises smoothly from 0 at `spray_start` to 1 at the top
//!    (h mapped to 1), toward `spray_color`.
//! 3. **Sky reflection**: the sky in the mirror direction r = d − 2(d·n)n (held at the
//!    horizon when it points down), weighted by Schlick's Fresnel term
//!    F = F0 + (1 − F0)(1 − n·v)^5, F0 = ((n_w − 1)/(n_w + 1))², water n_w = 1.33; or the
//!    report's pseudo-reflection w = 1 − (n·v)^C.
//! 4. **Sun specular**: w = (max(r·s, 0))^shininess toward the sun's color, s the unit
//!    direction toward the sun (none when the sun is below the horizon).
//! 5. **Whitecaps**: w = min(1, c/0.1), c ∈ [0, 1] the foam coverage clamp((T − J)/T, 0, 1)
//!    of a choppy field (foam hides the water where J is 10 % of T below T), toward foam,
//!    a rough white surface: albedo (0.92, 0.94, 0.95) lit diffusely,
//!    0.75 + 0.3·max(n·s, 0)/max(s_z, 0.2) (a flat patch under the sun gets the sum
//!    whatever the sun's height), no reflection or glitter.
//! 6. **Haze**: w = 1 − exp(−t/haze distance) toward the sky's horizon color, t the
//!    distance from the camera.
//!
//! **Terrain** (the `fractal` spectrum's fields) replaces steps 1–5: the albedo is grass
//! (0.30, 0.42, 0.20) below the mapped height 0.2, rock (0.45, 0.42, 0.38) above and on
//! slopes steeper than 35° (n_z < cos 35°, blended over 10°), snow (0.95, 0.96, 0.98) above
//! the mapped height 0.6 where the slope is under 40°, each change blended smoothly; lit by
//! a sky ambient 0.35 plus the sun's Lambert term 0.9·max(n·s, 0)/max(s_z, 0.2), then haze.
//!
//! The sky is a gradient from the horizon color to the zenith color, w = (d_z)^0.5 for a
//! ray going up (the horizon color below), plus a small sun disc. Colors are given as
//! sRGB values (the paper's, as displayed) and mixed in linear light; the image is
//! encoded back to 8-bit sRGB.

/// How the sky reflection is weighted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reflection {
    /// Schlick's approximation of Fresnel's law for a refractive index (water: 1.33).
    Fresnel { index: f64 },
    /// Li, He & Gong's pseudo-reflection 1 − (n·v)^C (they suggest C = 0.3).
    Pseudo { exponent: f64 },
}

/// The refractive index of water.
pub const WATER_INDEX: f64 = 1.33;
/// The exponent C of the pseudo-reflection suggested by Li, He & Gong.
pub const PSEUDO_EXPONENT: f64 = 0.3;
/// Light on foam from the sky, and from the sun on a patch facing it (× foam albedo).
pub const FOAM_AMBIENT: f64 = 0.75;
pub const FOAM_SUN: f64 = 0.3;
/// The foam coverage at which foam hides the water (J this fraction of T below T).
pub const FOAM_OPAQUE: f64 = 0.1;
/// The foam's albedo (sRGB).
pub const FOAM_ALBEDO: [f64; 3] = [0.92, 0.94, 0.95];
/// Light on terrain from the sky, and from the sun on a patch facing it (× albedo).
pub const TERRAIN_AMBIENT: f64 = 0.35;
pub const TERRAIN_SUN: f64 = 0.9;

/// Colors and lights (see the module docs). Colors are linear RGB; build them from sRGB
/// values with [`srgb`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting {
    /// Unit vector toward the sun.
    pub sun_dir: [f64; 3],
    pub sun_color: [f64; 3],
    /// Phong exponent of the sun's highlight.
    pub shininess: f64,
    pub reflection: Reflection,
    /// Distance at which the haze covers 1 − 1/e of the color, meters; infinite: no haze.
    pub haze_distance_m: f64,
    pub deep_color: [f64; 3],
    pub crest_color: [f64; 3],
    pub spray_color: [f64; 3],
    /// Mapped height (in [−1, 1]) where the spray starts.
    pub spray_start: f64,
    pub sky_horizon: [f64; 3],
    pub sky_zenith: [f64; 3],
}

/// A color given in sRGB (0 … 1), in linear light.
pub fn srgb(c: [f64; 3]) -> [f64; 3] {
    c.map(|v| {
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    })
}

/// A linear value encoded as an 8-bit sRGB value (clamped to 0 … 1 first).
pub fn encode_srgb8(v: f64) -> u8 {
    let v = if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let e = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0).round() as u8
}

/// The unit vector toward a sun at `azimuth_rad` (from +x toward +y) and `elevation_rad`.
pub fn sun_direction(azimuth_rad: f64, elevation_rad: f64) -> [f64; 3] {
    let (sa, ca) = azimuth_rad.sin_cos();
    let (se, ce) = elevation_rad.sin_cos();
    [ce * ca, ce * sa, se]
}

impl Default for Lighting {
    fn default() -> Self {
        Self {
            sun_dir: sun_direction(0.0, 25f64.to_radians()),
            sun_color: srgb([1.0, 0.96, 0.88]),
            shininess: 400.0,
            reflection: Reflection::Fresnel { index: WATER_INDEX },
            haze_distance_m: f64::INFINITY,
            deep_color: srgb([0.02, 0.05, 0.10]),
            crest_color: srgb([0.0, 0.64, 0.68]),
            spray_color: srgb([0.90, 0.94, 0.96]),
            spray_start: 0.55,
            sky_horizon: srgb([0.80, 0.86, 0.92]),
            sky_zenith: srgb([0.26, 0.46, 0.76]),
        }
    }
}

#[inline]
fn mix(c: [f64; 3], other: [f64; 3], w: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| c[k] + (other[k] - c[k]) * w)
}

#[inline]
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// max(cos, 0)^n, skipped (0) where it is below 1e-6: x^n ≤ e^(−n(1 − x)).
#[inline]
fn highlight(cos: f64, n: f64) -> f64 {
    if cos > 0.0 && n * (1.0 - cos) < 14.0 {
        cos.powf(n)
    } else {
        0.0
    }
}

/// Schlick's Fresnel reflectance for a cosine `cos_v` between normal and view.
pub fn schlick(index: f64, cos_v: f64) -> f64 {
    let f0 = ((index - 1.0) / (index + 1.0)).powi(2);
    f0 + (1.0 - f0) * (1.0 - cos_v.clamp(0.0, 1.0)).powi(5)
}

/// How a height maps to [−1, 1] for the height color and the spray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightScale {
    pub mean_m: f64,
    /// Largest deviation from the mean in the field, meters (0: flat, every height maps to 0).
    pub amplitude_m: f64,
}

impl HeightScale {
    #[inline]
    pub fn map(&self, h: f64) -> f64 {
        if self.amplitude_m > 0.0 {
            ((h - self.mean_m) / self.amplitude_m).clamp(-1.0, 1.0)
        } else {
            0.0
        }
    }
}

impl Lighting {
    /// The sky seen along unit direction `d`, without the sun's disc.
    pub fn sky(&self, d: [f64; 3]) -> [f64; 3] {
        mix(self.sky_horizon, self.sky_zenith, d[2].max(0.0).sqrt())
    }

    /// The sky of a ray that meets no sea: the gradient and the sun's disc.
    pub fn background(&self, d: [f64; 3]) -> [f64; 3] {
        let c = self.sky(d);
        if self.sun_dir[2] <= 0.0 {
            return c;
        }
        mix(c, self.sun_color, highlight(dot(d, self.sun_dir), 2000.0))
    }

    /// The weight of the sky reflection for a cosine `cos_v` = n·v.
    pub fn reflectance(&self, cos_v: f64) -> f64 {
        match self.reflection {
            Reflection::Fresnel { index } => schlick(index, cos_v),
            Reflection::Pseudo { exponent } => 1.0 - cos_v.clamp(0.0, 1.0).powf(exponent),
        }
    }

    /// The color of the sea at distance `t_m` along `d`, height `h` and normal `n`.
    pub fn sea(
        &self,
        d: [f64; 3],
        t_m: f64,
        h_m: f64,
        n: [f64; 3],
        scale: &HeightScale,
    ) -> [f64; 3] {
        let c = self.sea_unhazed(d, h_m, n, scale);
        self.haze(c, d, t_m)
    }

    /// Steps 1–4 of the module docs.
    fn sea_unhazed(&self, d: [f64; 3], h_m: f64, n: [f64; 3], scale: &HeightScale) -> [f64; 3] {
        let hm = scale.map(h_m);
        let mut c = mix(self.deep_color, self.crest_color, 0.5 * (hm + 1.0));
        let spray = smoothstep(self.spray_start, 1.0, hm);
        c = mix(c, self.spray_color, spray);
        let dn = dot(d, n);
        let cos_v = (-dn).max(0.0);
        let mut r = [0, 1, 2].map(|k| d[k] - 2.0 * dn * n[k]);
        if r[2] < 0.0 {
            r[2] = 0.0;
            let len = dot(r, r).sqrt();
            r = if len > 0.0 {
                r.map(|v| v / len)
            } else {
                [1.0, 0.0, 0.0]
            };
        }
        c = mix(c, self.sky(r), self.reflectance(cos_v));
        if self.sun_dir[2] > 0.0 {
            c = mix(
                c,
                self.sun_color,
                highlight(dot(r, self.sun_dir), self.shininess),
            );
        }
        c
    }

    /// [`sea`](Self::sea) with foam coverage `cover` ∈ [0, 1] drawn as whitecaps (step 5 of
    /// the module docs).
    pub fn sea_with_foam(
        &self,
        d: [f64; 3],
        t_m: f64,
        h_m: f64,
        n: [f64; 3],
        scale: &HeightScale,
        cover: f64,
    ) -> [f64; 3] {
        if cover <= 0.0 {
            return self.sea(d, t_m, h_m, n, scale);
        }
        let water = self.sea_unhazed(d, h_m, n, scale);
        let light = FOAM_AMBIENT + FOAM_SUN * self.sun_on(n);
        let foam = srgb(FOAM_ALBEDO).map(|a| a * light);
        self.haze(mix(water, foam, (cover / FOAM_OPAQUE).min(1.0)), d, t_m)
    }

    /// The sun's diffuse light on a patch of normal `n`, 1 for a flat patch (0 without sun).
    fn sun_on(&self, n: [f64; 3]) -> f64 {
        if self.sun_dir[2] <= 0.0 {
            return 0.0;
        }
        dot(n, self.sun_dir).max(0.0) / self.sun_dir[2].max(0.2)
    }

    /// Land at distance `t_m` along `d`, height `h` and normal `n` (see the module docs).
    pub fn terrain(
        &self,
        d: [f64; 3],
        t_m: f64,
        h_m: f64,
        n: [f64; 3],
        scale: &HeightScale,
    ) -> [f64; 3] {
        let hm = scale.map(h_m);
        let grass = srgb([0.30, 0.42, 0.20]);
        let rock = srgb([0.45, 0.42, 0.38]);
        let snow = srgb([0.95, 0.96, 0.98]);
        let (cos35, cos45, cos40, cos30) = (
            35f64.to_radians().cos(),
            45f64.to_radians().cos(),
            40f64.to_radians().cos(),
            30f64.to_radians().cos(),
        );
        let steep = 1.0 - smoothstep(cos45, cos35, n[2]);
        let high = smoothstep(0.1, 0.3, hm);
        let mut albedo = mix(grass, rock, high.max(steep));
        let snowy = smoothstep(0.5, 0.7, hm) * smoothstep(cos40, cos30, n[2]);
        albedo = mix(albedo, snow, snowy);
        let light = TERRAIN_AMBIENT + TERRAIN_SUN * self.sun_on(n);
        self.haze(albedo.map(|a| a * light), d, t_m)
    }

    /// `c` seen through the haze over `t_m` meters along `d`.
    pub fn haze(&self, c: [f64; 3], d: [f64; 3], t_m: f64) -> [f64; 3] {
        if self.haze_distance_m.is_finite() && self.haze_distance_m > 0.0 {
            let w = 1.0 - (-t_m / self.haze_distance_m).exp();
            mix(c, self.sky([d[0], d[1], 0.0]), w)
        } else {
            c
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schlick_meets_fresnel_at_normal_and_grazing_incidence() {
        // Normal incidence on water: ((1.33 − 1)/(1.33 + 1))² = 0.020 06.
        assert!((schlick(WATER_INDEX, 1.0) - 0.020_06).abs() < 1e-5);
        assert_eq!(schlick(WATER_INDEX, 0.0), 1.0);
        // Fresnel's unpolarized reflectance at 60° is 0.0591; Schlick gives 0.0507.
        const SCHLICK_TOL: f64 = 0.01;
        assert!((schlick(WATER_INDEX, 0.5) - 0.0591).abs() < SCHLICK_TOL);
    }

    #[test]
    fn srgb_round_trips_every_byte() {
        for b in 0..=255u8 {
            let v = b as f64 / 255.0;
            assert_eq!(encode_srgb8(srgb([v; 3])[0]), b, "byte {b}");
        }
        assert_eq!(encode_srgb8(f64::NAN), 0);
        assert_eq!(encode_srgb8(7.0), 255);
    }

    #[test]
    fn the_pseudo_reflection_is_one_minus_a_power_of_the_cosine() {
        let l = Lighting {
            reflection: Reflection::Pseudo {
                exponent: PSEUDO_EXPONENT,
            },
            ..Lighting::default()
        };
        assert_eq!(l.reflectance(1.0), 0.0);
        assert!((l.reflectance(0.5) - (1.0 - 0.5f64.powf(0.3))).abs() < 1e-15);
    }

    #[test]
    fn heights_map_from_deep_blue_to_light_green_and_spray() {
        let l = Lighting {
            sun_dir: sun_direction(0.0, -0.1),
            reflection: Reflection::Pseudo { exponent: 1e-9 },
            ..Lighting::default()
        };
        // Looking straight down with (n·v)^C ≈ 1: no reflection, the height color alone.
        let scale = HeightScale {
            mean_m: 1.0,
            amplitude_m: 2.0,
        };
        let down = [0.0, 0.0, -1.0];
        let up = [0.0, 0.0, 1.0];
        let trough = l.sea(down, 1.0, -1.0, up, &scale);
        let crest = l.sea(down, 1.0, 3.0, up, &scale);
        const COLOR_TOL: f64 = 1e-6;
        for k in 0..3 {
            assert!(
                (trough[k] - l.deep_color[k]).abs() < COLOR_TOL,
                "trough {trough:?}"
            );
            assert!(
                (crest[k] - l.spray_color[k]).abs() < COLOR_TOL,
                "crest {crest:?}"
            );
        }
        let middle = l.sea(down, 1.0, 1.0, up, &scale);
        let expected = mix(l.deep_color, l.crest_color, 0.5);
        assert!((0..3).all(|k| (middle[k] - expected[k]).abs() < COLOR_TOL));
    }

    #[test]
    fn haze_fades_to_the_horizon() {
        let l = Lighting {
            haze_distance_m: 100.0,
            ..Lighting::default()
        };
        let d = [1.0, 0.0, 0.0];
        let c = l.haze([0.0; 3], d, 100.0);
        let w = 1.0 - (-1f64).exp();
        assert!((0..3).all(|k| (c[k] - w * l.sky_horizon[k]).abs() < 1e-12));
    }
}
