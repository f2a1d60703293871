//! Values that accept several spellings: a size `512`, `[512, 256]` or `"512x256"`; an
//! extent `1000`, `[1000.0, 500.0]` or `"1000x500"`; a range `[-1, 1]` or `"-1:1"`; a β
//! `"paper"`, `"matched"` or a number. Each serializes in one canonical form.

use serde::de::{self, Deserializer};
use serde::{Deserialize, Serialize, Serializer};

#[derive(Deserialize)]
#[serde(untagged)]
enum NumOrPair<T> {
    One(T),
    Two([T; 2]),
    Text(String),
}

fn pair<'de, D, T>(d: D, sep: char, what: &str) -> Result<[T; 2], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + std::str::FromStr,
{
    match NumOrPair::<T>::deserialize(d)? {
        NumOrPair::One(v) => Ok([v, v]),
        NumOrPair::Two(p) => Ok(p),
        NumOrPair::Text(s) => {
            let parse = |t: &str| {
                t.trim().parse::<T>().map_err(|_| {
                    de::Error::custom(format!(
                        "invalid {what} `{s}`: expected a number or A{sep}B"
                    ))
                })
            };
            match s.split_once(sep) {
                Some((a, b)) => Ok([parse(a)?, parse(b)?]),
                None => {
                    let v = parse(&s)?;
                    Ok([v, v])
                }
            }
        }
    }
}

/// Grid size: N samples along x, M along y.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size2(pub [usize; 2]);

impl<'de> Deserialize<'de> for Size2 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        pair::<D, i64>(d, 'x', "size").and_then(|[a, b]| {
            let conv = |v: i64| {
                usize::try_from(v).map_err(|_| {
                    de::Error::custom(format!("grid.size must be ≥ 2 samples per side (got {v})"))
                })
            };
            Ok(Size2([conv(a)?, conv(b)?]))
        })
    }
}

impl Serialize for Size2 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

/// A pair of lengths in meters (x, y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent2(pub [f64; 2]);

impl<'de> Deserialize<'de> for Extent2 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        pair::<D, NumF64>(d, 'x', "extent").map(|[a, b]| Extent2([a.0, b.0]))
    }
}

impl Serialize for Extent2 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

/// A height range `[min_m, max_m]`, also written `"MIN:MAX"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range2(pub [f64; 2]);

impl<'de> Deserialize<'de> for Range2 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum R {
            Two([NumF64; 2]),
            Text(String),
        }
        match R::deserialize(d)? {
            R::Two([a, b]) => Ok(Range2([a.0, b.0])),
            R::Text(s) => {
                let bad = || {
                    de::Error::custom(format!(
                        "invalid height range `{s}`: expected MIN:MAX in meters"
                    ))
                };
                let (a, b) = s.split_once(':').ok_or_else(bad)?;
                let a = a.trim().parse::<f64>().map_err(|_| bad())?;
                let b = b.trim().parse::<f64>().map_err(|_| bad())?;
                Ok(Range2([a, b]))
            }
        }
    }
}

impl Serialize for Range2 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

/// A float that also accepts an integer (TOML keeps `512` and `512.0` apart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NumF64(pub f64);

impl<'de> Deserialize<'de> for NumF64 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum N {
            F(f64),
            I(i64),
        }
        Ok(NumF64(match N::deserialize(d)? {
            N::F(v) => v,
            N::I(v) => v as f64,
        }))
    }
}

impl std::str::FromStr for NumF64 {
    type Err = std::num::ParseFloatError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        s.parse().map(NumF64)
    }
}

/// How the Perlin field is weighted in the hybrid blend (Li Tian eq. 10):
/// β(x, y) = (1 − α(x, y)) · b · beta_scale, where b is
/// - `paper`: h0max = max over k of |h̃0(k)| (the paper's choice, the default);
/// - `matched`: std(h_fft)/std(h_perlin), so both fields carry the same spread;
/// - a number: b in meters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Beta {
    Paper,
    Matched,
    Meters(f64),
}

impl<'de> Deserialize<'de> for Beta {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum B {
            N(NumF64),
            S(String),
        }
        match B::deserialize(d)? {
            B::N(v) => Ok(Beta::Meters(v.0)),
            B::S(s) => match s.as_str() {
                "paper" => Ok(Beta::Paper),
                "matched" => Ok(Beta::Matched),
                other => other.parse::<f64>().map(Beta::Meters).map_err(|_| {
                    de::Error::custom(format!(
                        "blend.beta must be \"paper\", \"matched\" or a number of meters (got `{other}`)"
                    ))
                }),
            },
        }
    }
}

impl Serialize for Beta {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Beta::Paper => s.serialize_str("paper"),
            Beta::Matched => s.serialize_str("matched"),
            Beta::Meters(v) => s.serialize_f64(*v),
        }
    }
}
