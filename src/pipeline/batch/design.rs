//! Random designs of a batch: `--sample N --vary KEY=DIST` draws N points of a parameter
//! space, at random or by Latin hypercube, and each point becomes a job entry (with its
//! drawn values as assignments, so they are the job's parameters, its index columns and
//! its name).
//!
//! The draws are portable: varied key number `i` (in the order given) reads ChaCha8 stream
//! `i` of the key `S` (the design seed, little-endian in the first 8 of the 32 key bytes).
//! A uniform number is `((x >> 11) + ½) / 2^53` of the next 64-bit output `x` (never 0 or
//! 1); a permutation is Fisher–Yates from the last position down, each index drawn by
//! rejection (`x mod (i+1)` of the first `x` below the largest multiple of `i+1`). Every
//! distribution is the transform of that number by its quantile function, computed with
//! the crate's portable `exp` and `ln`; drawn values are kept to 6 significant digits, as
//! printed. A design is drawn whole before sharding, so a job's values depend only on the
//! design and its index.

use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::config::layers::{self, Assignment};
use crate::error::{Error, ParamError, Result};
use crate::fastmath::{exp, ln};

use super::plan::{JobSpec, MAX_JOBS, check_key};

/// A distribution of one varied key.
#[derive(Debug, Clone, PartialEq)]
pub enum Dist {
    /// `uniform:A:B`, A < B.
    Uniform { a: f64, b: f64 },
    /// `log-uniform:A:B`, 0 < A < B: ln of the value is uniform.
    LogUniform { a: f64, b: f64 },
    /// `normal:MEAN:SD` or `normal:MEAN:SD:MIN:MAX` (truncated to [MIN, MAX]).
    Normal {
        mean: f64,
        sd: f64,
        bounds: Option<(f64, f64)>,
    },
    /// `int:A:B`: each whole number from A to B (both included) equally likely.
    Int { a: i64, b: i64 },
    /// `choice:A|B|C`: each value equally likely.
    Choice(Vec<String>),
}

/// The forms a distribution may take, for error messages.
const FORMS: &str =
    "uniform:A:B, log-uniform:A:B, normal:MEAN:SD, normal:MEAN:SD:MIN:MAX, int:A:B or choice:A|B|C";

impl Dist {
    /// Parses a distribution as typed after `KEY=`.
    pub fn parse(text: &str) -> std::result::Result<Self, String> {
        let (kind, rest) = text
            .split_once(':')
            .ok_or_else(|| format!("`{text}` is not a distribution: expected {FORMS}"))?;
        let numbers = |want: &[usize]| -> std::result::Result<Vec<f64>, String> {
            let parts: Vec<&str> = rest.split(':').collect();
            if !want.contains(&parts.len()) {
                return Err(format!("`{text}`: expected {FORMS}"));
            }
            parts
                .iter()
                .map(|p| {
                    p.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| format!("`{p}` in `{text}` is not a finite number"))
                })
                .collect()
        };
        let dist = match kind.trim() {
            "uniform" => {
                let n = numbers(&[2])?;
                Dist::Uniform { a: n[0], b: n[1] }
            }
            "log-uniform" => {
                let n = numbers(&[2])?;
                Dist::LogUniform { a: n[0], b: n[1] }
            }
            "normal" => {
                let n = numbers(&[2, 4])?;
                Dist::Normal {
                    mean: n[0],
                    sd: n[1],
                    bounds: (n.len() == 4).then(|| (n[2], n[3])),
                }
            }
            "int" => {
                let parts: Vec<&str> = rest.split(':').collect();
                let ints: Vec<i64> = parts
                    .iter()
                    .map(|p| p.trim().parse::<i64>())
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|_| format!("`{text}`: int:A:B takes two whole numbers"))?;
                if ints.len() != 2 {
                    return Err(format!("`{text}`: int:A:B takes two whole numbers"));
                }
                Dist::Int {
                    a: ints[0],
                    b: ints[1],
                }
            }
            "choice" => {
                let values: Vec<String> = rest.split('|').map(|v| v.trim().to_string()).collect();
                if values.iter().any(String::is_empty) {
                    return Err(format!("`{text}`: choice:A|B|C takes non-empty values"));
                }
                Dist::Choice(values)
            }
            other => return Err(format!("unknown distribution `{other}`: expected {FORMS}")),
        };
        dist.check()
            .map(|()| dist)
            .map_err(|m| format!("`{text}`: {m}"))
    }

    /// The bounds each distribution needs.
    fn check(&self) -> std::result::Result<(), String> {
        match *self {
            Dist::Uniform { a, b } if a >= b => Err(format!("A must be < B (got {a} ≥ {b})")),
            Dist::LogUniform { a, b } if !(a > 0.0 && a < b) => {
                Err(format!("must have 0 < A < B (got A = {a}, B = {b})"))
            }
            Dist::Normal { sd, .. } if sd <= 0.0 => Err(format!("SD must be > 0 (got {sd})")),
            Dist::Normal {
                bounds: Some((lo, hi)),
                ..
            } if lo >= hi => Err(format!("MIN must be < MAX (got {lo} ≥ {hi})")),
            Dist::Normal {
                mean,
                sd,
                bounds: Some((lo, hi)),
            } if phi((hi - mean) / sd) - phi((lo - mean) / sd) < 1e-12 => Err(format!(
                "[MIN, MAX] = [{lo}, {hi}] holds no probability of a normal of mean {mean} and SD {sd}"
            )),
            Dist::Int { a, b } if a > b => Err(format!("A must be ≤ B (got {a} > {b})")),
            _ => Ok(()),
        }
    }

    /// The value at probability `u` in (0, 1), as text: the quantile function.
    pub fn at(&self, u: f64) -> String {
        match self {
            Dist::Uniform { a, b } => number(a + u * (b - a), *a, *b),
            Dist::LogUniform { a, b } => number(exp(ln(*a) + u * (ln(*b) - ln(*a))), *a, *b),
            Dist::Normal { mean, sd, bounds } => match bounds {
                None => number(mean + sd * normal_quantile(u), f64::MIN, f64::MAX),
                Some((lo, hi)) => {
                    let (pl, ph) = (phi((lo - mean) / sd), phi((hi - mean) / sd));
                    let p = (pl + u * (ph - pl)).clamp(1e-300, 1.0 - 1e-16);
                    number(mean + sd * normal_quantile(p), *lo, *hi)
                }
            },
            Dist::Int { a, b } => {
                let span = (*b as i128 - *a as i128 + 1) as f64;
                let k = ((u * span).floor() as i128).min(span as i128 - 1);
                (*a as i128 + k).to_string()
            }
            Dist::Choice(values) => {
                let k = ((u * values.len() as f64) as usize).min(values.len() - 1);
                values[k].clone()
            }
        }
    }

    /// Values whose validity stands for the whole distribution: the ends of a range, the
    /// mean of an untruncated normal, every choice.
    fn probes(&self) -> Vec<String> {
        match self {
            Dist::Uniform { a, b } | Dist::LogUniform { a, b } => {
                vec![format!("{a}"), format!("{b}")]
            }
            Dist::Normal {
                bounds: Some((lo, hi)),
                ..
            } => vec![format!("{lo}"), format!("{hi}")],
            Dist::Normal { mean, .. } => vec![format!("{mean}")],
            Dist::Int { a, b } => vec![a.to_string(), b.to_string()],
            Dist::Choice(v) => v.clone(),
        }
    }
}

/// `v` to 6 significant digits, kept within [lo, hi], in its shortest form.
fn number(v: f64, lo: f64, hi: f64) -> String {
    let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    let r = if rounded < lo || rounded > hi {
        v
    } else {
        rounded
    };
    format!("{r}")
}

/// The standard normal CDF Φ(x) = erfc(−x/√2)/2, with the Chebyshev fit of erfc of
/// Numerical Recipes (fractional error < 1.2e-7).
fn phi(x: f64) -> f64 {
    let z = -x / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.5 * z.abs());
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let erfc = t * exp(poly);
    0.5 * if z >= 0.0 { erfc } else { 2.0 - erfc }
}

/// The standard normal quantile Φ⁻¹(p), p in (0, 1): Acklam's rational approximation
/// (relative error < 1.2e-9).
fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    const LOW: f64 = 0.024_25;
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < LOW {
        tail((-2.0 * ln(p)).sqrt())
    } else if p > 1.0 - LOW {
        -tail((-2.0 * ln(1.0 - p)).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

/// One `--vary KEY=DIST`.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    pub key: String,
    pub dist: Dist,
    /// As typed, for error messages (`--vary hs=uniform:1:3`).
    pub origin: String,
}

impl Vary {
    /// Parses `KEY=DIST` and checks that the key is a parameter.
    pub fn parse(text: &str) -> Result<Self> {
        let origin = format!("--vary {text}");
        let bad = |message: String| Error::Set {
            origin: origin.clone(),
            message,
        };
        let (key, dist) = text
            .split_once('=')
            .ok_or_else(|| bad(format!("expected KEY=DIST with DIST one of {FORMS}")))?;
        let key = key.trim();
        if key.is_empty() {
            return Err(bad("the key is missing".into()));
        }
        let dist = Dist::parse(dist.trim()).map_err(bad)?;
        check_key(key, &dist.probes()[0], &origin)?;
        Ok(Self {
            key: key.to_string(),
            dist,
            origin,
        })
    }
}

/// How the points are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignKind {
    /// Each value drawn independently.
    Random,
    /// Latin hypercube: each of the N equal-probability strata of every key is hit once.
    Lhs,
}

impl DesignKind {
    pub fn parse(text: &str) -> Result<Self> {
        match text {
            "random" => Ok(Self::Random),
            "lhs" => Ok(Self::Lhs),
            _ => Err(ParamError {
                name: "--design".into(),
                allowed: "random or lhs".into(),
                got: text.into(),
            }
            .into()),
        }
    }
}

/// A random design: N points of the varied keys.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    pub kind: DesignKind,
    pub n: usize,
    pub seed: u64,
    pub varies: Vec<Vary>,
}

/// The ChaCha8 generator of stream `stream` under the design seed.
fn generator(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(stream);
    rng
}

/// A number in (0, 1) from the next output.
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
}

/// A whole number below `n` (n ≥ 1), by rejection.
fn below(rng: &mut ChaCha8Rng, n: u64) -> u64 {
    let limit = u64::MAX - u64::MAX % n;
    loop {
        let x = rng.next_u64();
        if x < limit {
            return x % n;
        }
    }
}

impl Design {
    /// Checks N and the varied keys, and that every varied key's range or choices give
    /// valid parameters over the batch's base (`resolve_with` of the varied keys'
    /// assignments), before anything is written.
    pub fn new(
        kind: DesignKind,
        n: usize,
        seed: u64,
        varies: Vec<Vary>,
        resolve_with: impl Fn(&[Assignment]) -> Result<()>,
    ) -> Result<Self> {
        if n == 0 || n > MAX_JOBS {
            return Err(ParamError {
                name: "--sample".into(),
                allowed: format!("a number of jobs from 1 to {MAX_JOBS}"),
                got: n.to_string(),
            }
            .into());
        }
        if varies.is_empty() {
            return Err(ParamError {
                name: "--sample".into(),
                allowed: "given with at least one --vary KEY=DIST".into(),
                got: format!("--sample {n} alone"),
            }
            .into());
        }
        for (i, v) in varies.iter().enumerate() {
            if let Some(w) = varies[..i]
                .iter()
                .find(|w| layers::canonical_key(&w.key) == layers::canonical_key(&v.key))
            {
                return Err(Error::Set {
                    origin: v.origin.clone(),
                    message: format!("`{}` is varied twice (also by {})", v.key, w.origin),
                });
            }
        }
        // Each probe of a key with the first probe of every other key (a key may need
        // another one: --vary hs=… with --vary tp=…).
        let firsts: Vec<Assignment> = varies
            .iter()
            .map(|v| Assignment {
                origin: v.origin.clone(),
                key: v.key.clone(),
                value: v.dist.probes()[0].clone(),
            })
            .collect();
        for (i, v) in varies.iter().enumerate() {
            for probe in v.dist.probes() {
                let mut with = firsts.clone();
                with[i].value = probe.clone();
                resolve_with(&with).map_err(|e| Error::Set {
                    origin: v.origin.clone(),
                    message: format!(
                        "the value {probe} does not give valid parameters: {}",
                        e.to_string().trim_start_matches(&format!("{}: ", v.origin))
                    ),
                })?;
            }
        }
        Ok(Self {
            kind,
            n,
            seed,
            varies,
        })
    }

    /// The probabilities in (0, 1) of every point for varied key number `k`.
    pub fn probabilities(&self, k: usize) -> Vec<f64> {
        let mut rng = generator(self.seed, k as u64);
        let mut u: Vec<f64> = (0..self.n).map(|_| unit(&mut rng)).collect();
        if self.kind == DesignKind::Lhs {
            let mut perm: Vec<usize> = (0..self.n).collect();
            for i in (1..self.n).rev() {
                perm.swap(i, below(&mut rng, i as u64 + 1) as usize);
            }
            let n = self.n as f64;
            for (x, &p) in u.iter_mut().zip(&perm) {
                *x = (p as f64 + *x) / n;
            }
        }
        u
    }

    /// The drawn values as text: `points[job][key]`, keys in the order given.
    pub fn points(&self) -> Vec<Vec<String>> {
        let columns: Vec<Vec<String>> = self
            .varies
            .iter()
            .enumerate()
            .map(|(k, v)| {
                self.probabilities(k)
                    .into_iter()
                    .map(|u| v.dist.at(u))
                    .collect()
            })
            .collect();
        (0..self.n)
            .map(|j| columns.iter().map(|c| c[j].clone()).collect())
            .collect()
    }

    /// Each of `entries` (the manifest's jobs, or one job of the base) once per point, the
    /// point's values as its assignments: entry-major, then the point's index.
    pub fn entries(&self, entries: &[JobSpec]) -> Result<Vec<JobSpec>> {
        if entries.len().saturating_mul(self.n) > MAX_JOBS {
            return Err(Error::Set {
                origin: format!("--sample {}", self.n),
                message: format!("the design gives more than {MAX_JOBS} jobs"),
            });
        }
        let points = self.points();
        Ok(entries
            .iter()
            .flat_map(|e| {
                points.iter().map(move |p| {
                    let mut e = e.clone();
                    for (v, value) in self.varies.iter().zip(p) {
                        e.assignments.push(Assignment {
                            origin: format!("--vary {}={value}", v.key),
                            key: v.key.clone(),
                            value: value.clone(),
                        });
                    }
                    e
                })
            })
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn design(kind: DesignKind, n: usize, seed: u64, varies: &[&str]) -> Design {
        let v = varies.iter().map(|t| Vary::parse(t).unwrap()).collect();
        Design::new(kind, n, seed, v, |_| Ok(())).unwrap()
    }

    #[test]
    fn the_first_draws_of_chacha8_are_pinned() {
        // ChaCha8 (8 rounds), key = seed 7 little-endian then zeros, stream 0: the 64-bit
        // outputs are fixed by the cipher. A change here changes every design.
        let mut rng = generator(7, 0);
        let first: Vec<u64> = (0..3).map(|_| rng.next_u64()).collect();
        let mut again = generator(7, 0);
        assert_eq!(first[0], again.next_u64());
        assert_eq!(
            first,
            [PIN_0, PIN_1, PIN_2],
            "ChaCha8 outputs of seed 7, stream 0"
        );
        let d = design(DesignKind::Random, 3, 7, &["wind-speed=uniform:5:15"]);
        let want: Vec<String> = first
            .iter()
            .map(|&x| {
                let u = ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
                number(5.0 + 10.0 * u, 5.0, 15.0)
            })
            .collect();
        let got: Vec<String> = d.points().into_iter().map(|p| p[0].clone()).collect();
        assert_eq!(
            got, want,
            "uniform values are the transform of the pinned outputs"
        );
        assert_eq!(got, PIN_VALUES, "the first values of the design");
    }

    const PIN_0: u64 = 14_095_323_943_061_994_099;
    const PIN_1: u64 = 8_595_031_940_432_502_117;
    const PIN_2: u64 = 104_676_313_501_531_310;
    const PIN_VALUES: [&str; 3] = ["12.6411", "9.65938", "5.05675"];

    #[test]
    fn lhs_hits_every_stratum_of_every_key_once() {
        for n in [1, 2, 7, 50] {
            let d = design(
                DesignKind::Lhs,
                n,
                3,
                &["hs=uniform:1:3", "wind-dir=normal:0:30", "seed=int:0:9"],
            );
            for k in 0..3 {
                let mut strata: Vec<usize> = d
                    .probabilities(k)
                    .iter()
                    .map(|u| (u * n as f64).floor() as usize)
                    .collect();
                strata.sort_unstable();
                assert_eq!(strata, (0..n).collect::<Vec<_>>(), "n {n}, key {k}");
            }
        }
        // Mapped through the uniform quantile, each stratum of [1, 3] holds one value.
        let d = design(DesignKind::Lhs, 8, 11, &["hs=uniform:1:3"]);
        let mut bins: Vec<usize> = d
            .points()
            .iter()
            .map(|p| ((p[0].parse::<f64>().unwrap() - 1.0) / 2.0 * 8.0).floor() as usize)
            .collect();
        bins.sort_unstable();
        assert_eq!(bins, (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn random_draws_follow_their_distributions() {
        const N: usize = 4000;
        let d = design(
            DesignKind::Random,
            N,
            5,
            &[
                "hs=uniform:1:3",
                "wind-speed=log-uniform:1:100",
                "wind-dir=normal:10:2",
                "seed=int:1:4",
                "spectrum=choice:jonswap|phillips",
                "tp=normal:8:4:6:9",
            ],
        );
        let pts = d.points();
        let col = |k: usize| -> Vec<f64> { pts.iter().map(|p| p[k].parse().unwrap()).collect() };
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        // Standard errors at N = 4000 are ~1/60 of a standard deviation; 5 of them allowed.
        let u = col(0);
        assert!(u.iter().all(|&x| (1.0..=3.0).contains(&x)));
        assert!((mean(&u) - 2.0).abs() < 5.0 * 0.577 / 63.0);
        let logs: Vec<f64> = col(1).iter().map(|x| x.log10()).collect();
        assert!(
            (mean(&logs) - 1.0).abs() < 5.0 * 0.577 / 63.0,
            "log10 uniform on [0, 2]"
        );
        let n = col(2);
        let m = mean(&n);
        let sd = (n.iter().map(|x| (x - m).powi(2)).sum::<f64>() / N as f64).sqrt();
        assert!((m - 10.0).abs() < 5.0 * 2.0 / 63.0, "mean {m}");
        assert!((sd - 2.0).abs() < 0.1, "sd {sd}");
        let ints = col(3);
        for v in 1..=4 {
            let c = ints.iter().filter(|&&x| x == v as f64).count() as f64 / N as f64;
            assert!((c - 0.25).abs() < 0.035, "int {v}: {c}");
        }
        let jon = pts.iter().filter(|p| p[4] == "jonswap").count() as f64 / N as f64;
        assert!((jon - 0.5).abs() < 0.04);
        assert!(
            col(5).iter().all(|&x| (6.0..=9.0).contains(&x)),
            "truncated"
        );
    }

    #[test]
    fn quantiles_invert_the_normal_cdf() {
        for p in [1e-6, 0.01, 0.1, 0.3, 0.5, 0.8, 0.975, 0.999_999] {
            let x = normal_quantile(p);
            assert!(
                (phi(x) - p).abs() < 2e-7 * p.max(1e-3),
                "p {p}: x {x}, Φ {}",
                phi(x)
            );
        }
        assert!((normal_quantile(0.975) - 1.959_963_985).abs() < 1e-8);
        assert!((phi(1.0) - 0.841_344_746).abs() < 1e-7);
    }

    #[test]
    fn bad_designs_name_the_part_at_fault() {
        let err = |t: &str| Vary::parse(t).unwrap_err().to_string();
        assert!(
            err("hs=uniform:3:1").contains("A must be < B"),
            "{}",
            err("hs=uniform:3:1")
        );
        assert!(err("hs=log-uniform:0:1").contains("0 < A < B"));
        assert!(err("hs=normal:1:0").contains("SD must be > 0"));
        assert!(err("hs=normal:1:1:5:2").contains("MIN must be < MAX"));
        assert!(err("seed=int:5:1").contains("A must be ≤ B"));
        assert!(err("seed=int:1.5:3").contains("two whole numbers"));
        assert!(err("hs=gamma:1:2").contains("unknown distribution `gamma`"));
        assert!(err("hs=uniform:1").contains("expected uniform:A:B"));
        assert!(err("bogus=uniform:1:2").contains("unknown key `bogus`"));
        assert!(err("spectrum=choice:jonswap||x").contains("non-empty"));
        let v = vec![Vary::parse("spectrum=choice:jonswap|foam").unwrap()];
        let e = Design::new(DesignKind::Random, 4, 1, v, |a| {
            layers::resolve(None, a).map(|_| ())
        })
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("--vary spectrum=choice:jonswap|foam") && e.contains("foam"),
            "{e}"
        );
        let v = vec![Vary::parse("hs=uniform:1:2").unwrap()];
        let e = Design::new(DesignKind::Random, 0, 1, v, |_| Ok(())).unwrap_err();
        assert!(e.to_string().contains("--sample must be"), "{e}");
    }

    #[test]
    fn the_entries_repeat_each_job_for_every_point() {
        let d = design(DesignKind::Lhs, 3, 9, &["hs=uniform:1:3", "tp=uniform:6:9"]);
        let base = [
            JobSpec {
                preset: None,
                assignments: vec![Assignment::flag("seed", "1")],
            },
            JobSpec {
                preset: Some("calm".into()),
                assignments: Vec::new(),
            },
        ];
        let e = d.entries(&base).unwrap();
        assert_eq!(e.len(), 6);
        let pts = d.points();
        assert_eq!(e[4].preset.as_deref(), Some("calm"));
        assert_eq!(e[4].assignments[0].value, pts[1][0]);
        assert_eq!(e[2].assignments[2].value, pts[2][1]);
        assert_eq!(d.points(), pts, "the same design twice");
    }
}
