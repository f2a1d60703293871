//! Intersecting rays with the height field, accelerated by the max-height quadtree of
//! [`Pyramid`] as in Mastin et al. (1987): boxes whose top lies below the ray are skipped
//! whole, and the surface itself is intersected only in the leaves.
//!
//! The traversal is the stackless form of Mastin's stack of boxes: the ray walks the nodes
//! of one level of the quadtree in order along x and y (a 2D DDA on integer cell indices,
//! so cell boundaries are never lost to rounding); a node the ray passes above is skipped
//! and the walk goes up a level, a node it may hit is opened (down a level), and in a leaf
//! the ray is intersected exactly with a bilinear patch (a quadratic in the ray parameter).
//!
//! **Distance low-pass.** A ray's footprint grows with distance t as
//! w(t) = t·θ/√max(|d_z|, 0.01) (θ the angular spacing of the samples, d_z the ray's
//! vertical direction: a geometric mean of the footprint across and along a grazing ray).
//! The surface seen at t is H = (1 − f)·S_L + f·S_L+1, the mean levels around
//! λ = log2(w/√(dx·dy)) = L + f; leaves are the nodes of level L. λ is frozen over one leaf,
//! which makes H a bilinear patch there; a ray found already below the patch at a leaf's
//! entry (possible only where λ changed between leaves) hits at that entry, so no ray can
//! slip through. Past the last level the surface is the flat mean plane.
//!
//! **Beyond the field.** A periodic field (`wrap`) repeats without end. Otherwise the
//! field sits in a flat sea at its mean height (the same plane), so a view is never a
//! floating square.

use super::pyramid::{Pyramid, bilinear, widen};

/// Where a ray meets the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter (distance along a unit direction), meters.
    pub t: f64,
    /// The point hit, meters (x and y unwrapped: outside [0, L) on repeats).
    pub point: [f64; 3],
    /// Height and slopes of the surface there (of the low-passed surface at a distance).
    pub height_m: f64,
    pub slope: [f64; 2],
}

impl Hit {
    /// The level-0 cell (possibly on a repeat) that contains the point hit.
    pub fn cell(&self, pyr: &Pyramid) -> (i64, i64) {
        (
            (self.point[0] / pyr.dx_m).floor() as i64,
            (self.point[1] / pyr.dy_m).floor() as i64,
        )
    }

    /// Unit normal of the surface, from the slopes: (−∂h/∂x, −∂h/∂y, 1)/|…|.
    pub fn normal(&self) -> [f64; 3] {
        let n = [-self.slope[0], -self.slope[1], 1.0];
        let len = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
        n.map(|c| c / len)
    }
}

/// A ray: origin and unit direction, meters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: [f64; 3],
    pub dir: [f64; 3],
}

impl Ray {
    #[inline]
    pub fn at(&self, t: f64) -> [f64; 3] {
        [0, 1, 2].map(|k| self.origin[k] + self.dir[k] * t)
    }
}

/// How the surface is low-passed with distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lod {
    /// Angular spacing of the samples through the image, radians; 0 turns the low-pass off.
    pub angle_rad: f64,
}

/// Steps after which a ray is given up (a guard; no ray of a finite render takes as many).
const MAX_STEPS: usize = 1 << 22;

/// A traversal of one pyramid.
pub struct Tracer<'a> {
    pub pyr: &'a Pyramid,
    pub lod: Lod,
    /// Rays end here, meters.
    pub max_distance_m: f64,
}

/// A node of max level `l`: its level-0 cells [x0, x1) × [y0, y1) (unwrapped) and its
/// index in the level.
struct Node {
    x0: i64,
    x1: i64,
    y0: i64,
    y1: i64,
    i: usize,
    j: usize,
}

impl<'a> Tracer<'a> {
    pub fn new(pyr: &'a Pyramid, lod: Lod) -> Self {
        Self {
            pyr,
            lod,
            max_distance_m: f64::INFINITY,
        }
    }

    /// The fraction f of λ = L + f at t for a ray whose footprint grows by `k` sample
    /// spacings per meter, given L.
    #[inline]
    fn lod_fraction(k: f64, t: f64, level: usize) -> f64 {
        let w = k * t;
        if w > 1.0 {
            (w.log2() - level as f64).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The node of max level `l` that holds level-0 cell (cx, cy).
    #[inline]
    fn node(&self, l: usize, cx: i64, cy: i64) -> Node {
        let p = self.pyr;
        let axis = |c: i64, n: usize| -> (i64, i64, usize) {
            let (tile, local) = if p.wrap { split(c, n) } else { (0, c) };
            let n = n as i64;
            let k = local >> l;
            let start = tile * n + (k << l);
            let end = (start + (1i64 << l)).min((tile + 1) * n);
            (start, end, k as usize)
        };
        let (x0, x1, i) = axis(cx, p.cells_x);
        let (y0, y1, j) = axis(cy, p.cells_y);
        Node {
            x0,
            x1,
            y0,
            y1,
            i,
            j,
        }
    }

    /// The mean plane as the surface: the hit of `ray` at or after `t`, if any.
    fn plane_hit(&self, ray: &Ray, t: f64) -> Option<Hit> {
        let m = self.pyr.mean_m;
        let z = ray.origin[2] + ray.dir[2] * t;
        let th = if z <= m {
            t
        } else if ray.dir[2] < 0.0 {
            (ray.origin[2] - m) / -ray.dir[2]
        } else {
            return None;
        };
        (th <= self.max_distance_m).then(|| {
            let mut point = ray.at(th);
            point[2] = m;
            Hit {
                t: th,
                point,
                height_m: m,
                slope: [0.0, 0.0],
            }
        })
    }

    /// The first hit of `ray` (unit direction) with the surface.
    pub fn trace(&self, ray: &Ray) -> Option<Hit> {
        let p = self.pyr;
        let [ox, oy, oz] = ray.origin;
        let [dx, dy, dz] = ray.dir;
        let top = p.global_max() as f64;
        // Start where the ray comes down to the top of everything.
        let mut t = if oz > top {
            if dz >= 0.0 {
                return None;
            }
            (oz - top) / -dz
        } else {
            0.0
        };
        let cell_w = (p.dx_m * p.dy_m).sqrt();
        let k_lod = if self.lod.angle_rad > 0.0 {
            self.lod.angle_rad / dz.abs().max(0.01).sqrt() / cell_w
        } else {
            0.0
        };
        let top_mean = p.top_mean();
        // Outside a non-periodic field: the mean plane.
        let mut t_end = f64::INFINITY;
        if !p.wrap {
            let (xe, ye) = (p.cells_x as f64 * p.dx_m, p.cells_y as f64 * p.dy_m);
            let slab = |o: f64, d: f64, hi: f64| -> (f64, f64) {
                if d != 0.0 {
                    let (a, b) = ((0.0 - o) / d, (hi - o) / d);
                    (a.min(b), a.max(b))
                } else if (0.0..=hi).contains(&o) {
                    (f64::NEG_INFINITY, f64::INFINITY)
                } else {
                    (f64::INFINITY, f64::NEG_INFINITY)
                }
            };
            let (ax, bx) = slab(ox, dx, xe);
            let (ay, by) = slab(oy, dy, ye);
            let (enter, exit) = (ax.max(ay), bx.min(by));
            if exit < enter || exit <= t {
                return self.plane_hit(ray, 0.0);
            }
            if let Some(h) = self.plane_hit(ray, 0.0).filter(|h| h.t < enter.max(t)) {
                return Some(h);
            }
            t = t.max(enter);
            t_end = exit;
        }
        let (inv_dx, inv_dy) = (1.0 / p.dx_m, 1.0 / p.dy_m);
        let cell_of = |t: f64| -> (i64, i64) {
            let [x, y, _] = ray.at(t);
            let (mut cx, mut cy) = ((x * inv_dx).floor() as i64, (y * inv_dy).floor() as i64);
            if !p.wrap {
                cx = cx.clamp(0, p.cells_x as i64 - 1);
                cy = cy.clamp(0, p.cells_y as i64 - 1);
            }
            (cx, cy)
        };
        let (mut cx, mut cy) = cell_of(t);
        let top_max = p.top_max();
        // Start at the level of the nodes as wide as the ray's run through the band of
        // heights (a descending ray crosses it within that distance).
        let mut l = if dz < 0.0 {
            let run = (top - p.min_m) / -dz * dx.hypot(dy) / cell_w;
            if run > 1.0 {
                (run.log2().ceil() as usize).min(top_max)
            } else {
                0
            }
        } else {
            top_max
        };
        // L = ⌊λ⌋ grows with t: it passes L + 1 where k·t = 2^(L+1).
        let mut lod_level = 0usize;
        let mut next_level_t = if k_lod > 0.0 {
            2.0 / k_lod
        } else {
            f64::INFINITY
        };
        let (inv_dirx, inv_diry) = (1.0 / dx, 1.0 / dy);
        for _ in 0..MAX_STEPS {
            if t > self.max_distance_m {
                return None;
            }
            if !p.wrap && (cx < 0 || cy < 0 || cx >= p.cells_x as i64 || cy >= p.cells_y as i64) {
                // Left the field: the plane around it.
                return self.plane_hit(ray, t.min(t_end));
            }
            while t >= next_level_t {
                lod_level += 1;
                next_level_t *= 2.0;
            }
            if lod_level > top_mean {
                return self.plane_hit(ray, t);
            }
            let n = self.node(l, cx, cy);
            let tx = if dx > 0.0 {
                (n.x1 as f64 * p.dx_m - ox) * inv_dirx
            } else if dx < 0.0 {
                (n.x0 as f64 * p.dx_m - ox) * inv_dirx
            } else {
                f64::INFINITY
            };
            let ty = if dy > 0.0 {
                (n.y1 as f64 * p.dy_m - oy) * inv_diry
            } else if dy < 0.0 {
                (n.y0 as f64 * p.dy_m - oy) * inv_diry
            } else {
                f64::INFINITY
            };
            let t_exit = tx.min(ty).max(t);
            let z_in = oz + dz * t;
            let z_out = oz + dz * t_exit;
            let below = z_in.min(z_out);
            if below > p.node_max(l, n.i, n.j) as f64 {
                // The ray passes above this box.
            } else if l > lod_level {
                l -= 1;
                continue;
            } else if let Some(hit) = {
                let frac = Self::lod_fraction(k_lod, t, lod_level);
                self.leaf(ray, &n, lod_level, frac, t, t_exit)
            } {
                return (hit.t <= self.max_distance_m).then_some(hit);
            }
            if !t_exit.is_finite() || (dz >= 0.0 && z_out > top) {
                return None;
            }
            // Step into the next node along the ray.
            if tx <= ty {
                cx = if dx > 0.0 { n.x1 } else { n.x0 - 1 };
            }
            if ty <= tx {
                cy = if dy > 0.0 { n.y1 } else { n.y0 - 1 };
            }
            if tx < ty {
                cy = floor_i64(ray.at(t_exit)[1] * inv_dy).clamp(n.y0, n.y1 - 1);
            } else if ty < tx {
                cx = floor_i64(ray.at(t_exit)[0] * inv_dx).clamp(n.x0, n.x1 - 1);
            }
            t = t_exit;
            l = (l + 1).min(top_max);
        }
        None
    }

    /// The four corners of the patch of H over the mean-level-`lvl` cell holding the node
    /// (blended with level `lvl` + 1 by `frac`), with the cell's origin and size, meters.
    fn patch(&self, n: &Node, lvl: usize, frac: f64) -> ([[f64; 3]; 4], [f64; 2], [f64; 2]) {
        let p = self.pyr;
        let origin = |c0: i64, cells: usize| -> (usize, i64) {
            let (tile, local) = if p.wrap { split(c0, cells) } else { (0, c0) };
            let k = local >> lvl;
            (k as usize, tile * cells as i64 + (k << lvl))
        };
        let (i, x0) = origin(n.x0, p.cells_x);
        let (j, y0) = origin(n.y0, p.cells_y);
        let lv = &p.mean[lvl];
        let offsets = [(0, 0), (1, 0), (0, 1), (1, 1)];
        let mut c = lv.corners(i, j, p.wrap).map(widen);
        if frac > 0.0 {
            let coarse: [[f64; 3]; 4] = if lvl < p.top_mean() {
                let up = &p.mean[lvl + 1];
                let uc = up.corners(i >> 1, j >> 1, p.wrap).map(widen);
                // Corners of this cell in the coarser cell: 0, ½ or 1.
                offsets.map(|(a, b)| {
                    let u = ((i & 1) + a) as f64 * 0.5;
                    let v = ((j & 1) + b) as f64 * 0.5;
                    bilinear(uc, u, v)
                })
            } else {
                [[p.mean_m, 0.0, 0.0]; 4]
            };
            for (ck, kk) in c.iter_mut().zip(coarse) {
                for m in 0..3 {
                    ck[m] += (kk[m] - ck[m]) * frac;
                }
            }
        }
        let size = (1u64 << lvl) as f64;
        (
            c,
            [x0 as f64 * p.dx_m, y0 as f64 * p.dy_m],
            [size * p.dx_m, size * p.dy_m],
        )
    }

    /// Intersection with the patch over node `n` for t in [t0, t1].
    fn leaf(&self, ray: &Ray, n: &Node, lvl: usize, frac: f64, t0: f64, t1: f64) -> Option<Hit> {
        let (c, origin, size) = self.patch(n, lvl, frac);
        let [x, y, z] = ray.at(t0);
        let ua = (x - origin[0]) / size[0];
        let va = (y - origin[1]) / size[1];
        let du = ray.dir[0] / size[0];
        let dv = ray.dir[1] / size[1];
        let s = patch_root(c, [ua, va, z], [du, dv, ray.dir[2]], t1 - t0)?;
        let t = t0 + s;
        let (u, v) = (ua + du * s, va + dv * s);
        let [h, sx, sy] = bilinear(c, u, v);
        let mut point = ray.at(t);
        point[2] = h;
        Some(Hit {
            t,
            point,
            height_m: h,
            slope: [sx, sy],
        })
    }
}

/// ⌊v⌋ as an integer, without a call to the C library's floor.
#[inline]
fn floor_i64(v: f64) -> i64 {
    let i = v as i64;
    if (i as f64) > v { i - 1 } else { i }
}

/// (repeat, index within it) of level-0 cell `c` on an axis of `n` cells.
#[inline]
fn split(c: i64, n: usize) -> (i64, i64) {
    let n = n as i64;
    if (0..n).contains(&c) {
        (0, c)
    } else if n & (n - 1) == 0 {
        (c >> n.trailing_zeros(), c & (n - 1))
    } else {
        (c.div_euclid(n), c.rem_euclid(n))
    }
}

/// Smallest s in [0, s1] where the ray (u, v, z)(s) = a + d·s meets the bilinear patch of
/// heights `c[·][0]` over (u, v) ∈ cell; 0 when the ray starts below it.
pub fn patch_root(c: [[f64; 3]; 4], a: [f64; 3], d: [f64; 3], s1: f64) -> Option<f64> {
    let h00 = c[0][0];
    let b = c[1][0] - h00;
    let cc = c[2][0] - h00;
    let e = h00 - c[1][0] - c[2][0] + c[3][0];
    let [ua, va, za] = a;
    let [du, dv, dz] = d;
    // g(s) = z(s) − H(u(s), v(s)) = c0 + c1·s + c2·s²
    let c0 = za - (h00 + b * ua + cc * va + e * ua * va);
    if c0 <= 0.0 {
        return Some(0.0);
    }
    let c1 = dz - b * du - cc * dv - e * (ua * dv + va * du);
    let c2 = -e * du * dv;
    let g = |s: f64| c0 + s * (c1 + s * c2);
    let s1 = if s1.is_finite() {
        s1
    } else if c2 == 0.0 && c1 < 0.0 {
        -c0 / c1 * 2.0
    } else if c2 == 0.0 {
        return None;
    } else {
        // A parabola: its roots bound where it can cross.
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return None;
        }
        (disc.sqrt() + c1.abs()) / c2.abs() + 1.0
    };
    let mut best: Option<f64> = None;
    let mut take = |s: f64| {
        if s.is_finite() && (0.0..=s1).contains(&s) && best.is_none_or(|b| s < b) {
            best = Some(s);
        }
    };
    if c2.abs() <= 1e-12 * (c1.abs() + c0.abs() / s1.max(1e-300)) {
        if c1 < 0.0 {
            take(-c0 / c1);
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc >= 0.0 {
            let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
            if q != 0.0 {
                take(q / c2);
                take(c0 / q);
            }
        }
    }
    if best.is_none() && g(s1) <= 0.0 {
        // A crossing the root formulas lost to rounding: the secant of the ends.
        let g1 = g(s1);
        best = Some(s1 * c0 / (c0 - g1));
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::{Grid, GridSpec};
    use crate::render::pyramid::central_slopes;

    fn pyramid(grid: &Grid, wrap: bool) -> Pyramid {
        let (sx, sy) = central_slopes(grid, wrap);
        Pyramid::new(grid, &sx, &sy, wrap)
    }

    fn unit(d: [f64; 3]) -> [f64; 3] {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        d.map(|c| c / n)
    }

    /// A deterministic uniform number in [0, 1) from (seed, k).
    fn uniform(seed: u64, k: u64) -> f64 {
        (crate::rng::hash_words(&[seed, k]) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A smooth random field: a few random cosines plus small per-sample noise.
    fn rough_field(n: usize, extent: f64) -> Grid {
        let spec = GridSpec::new(n, n, extent, extent);
        let data = (0..n * n)
            .map(|k| {
                let (i, j) = ((k % n) as f64, (k / n) as f64);
                let x = i * spec.dx_m();
                let y = j * spec.dy_m();
                let w = std::f64::consts::TAU / extent;
                let h = 1.0 * (w * (3.0 * x + y)).cos()
                    + 0.5 * (w * (-2.0 * x + 5.0 * y) + 1.0).cos()
                    + 0.3 * (uniform(7, k as u64) - 0.5);
                h as f32
            })
            .collect();
        Grid::new(spec, data)
    }

    /// Brute force: the level-0 bilinear surface sampled at tiny steps along the ray, the
    /// first sign change refined by bisection. Independent of the quadtree and of
    /// [`patch_root`].
    fn march(pyr: &Pyramid, ray: &Ray, t_max: f64) -> Option<(f64, [f64; 3])> {
        let step = 0.002 * pyr.dx_m.min(pyr.dy_m);
        let g = |t: f64| {
            let [x, y, z] = ray.at(t);
            z - pyr.surface(0, x, y)[0]
        };
        let mut t = 0.0;
        while t < t_max {
            let t1 = t + step;
            if g(t1) <= 0.0 {
                let (mut a, mut b) = (t, t1);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if g(m) > 0.0 { a = m } else { b = m }
                }
                return Some((b, ray.at(b)));
            }
            t = t1;
        }
        None
    }

    #[test]
    fn the_quadtree_finds_the_same_hits_as_brute_force_marching() {
        const N: usize = 64;
        const EXTENT_M: f64 = 64.0;
        const RAYS: u64 = 300;
        // t of the two methods: the bisection's and the quadratic's rounding, far below a cell.
        const T_TOL_M: f64 = 1e-6;
        let grid = rough_field(N, EXTENT_M);
        for wrap in [true, false] {
            let pyr = pyramid(&grid, wrap);
            let mut tracer = Tracer::new(&pyr, Lod { angle_rad: 0.0 });
            tracer.max_distance_m = 200.0;
            let (mut hits, mut misses) = (0, 0);
            for k in 0..RAYS {
                let r = |m: u64| uniform(11 + m, k);
                // Cameras over the field (and around it, on repeats), rays down at
                // 5° … 60° in any direction.
                let (lo, span) = if wrap { (-40.0, 150.0) } else { (0.0, 63.0) };
                let origin = [lo + span * r(0), lo + span * r(1), 2.5 + 4.0 * r(2)];
                let yaw = std::f64::consts::TAU * r(3);
                let pitch = -(5.0 + 55.0 * r(4)).to_radians();
                let dir = [
                    yaw.cos() * pitch.cos(),
                    yaw.sin() * pitch.cos(),
                    pitch.sin(),
                ];
                let ray = Ray {
                    origin,
                    dir: unit(dir),
                };
                // Strictly inside: a hit on the edge of a non-periodic field may be the plane.
                let interior = |p: [f64; 3]| {
                    (0.0..63.0).contains(&p[0])
                        && p[0] > 0.0
                        && (0.0..63.0).contains(&p[1])
                        && p[1] > 0.0
                };
                let inside = |p: [f64; 3]| {
                    wrap || (0.0..=63.0).contains(&p[0]) && (0.0..=63.0).contains(&p[1])
                };
                let fast = tracer.trace(&ray);
                let slow = march(&pyr, &ray, 200.0);
                match (fast, slow) {
                    (Some(f), Some((t, p))) if inside(p) => {
                        hits += 1;
                        let cell = (
                            (p[0] / pyr.dx_m).floor() as i64,
                            (p[1] / pyr.dy_m).floor() as i64,
                        );
                        assert_eq!(
                            f.cell(&pyr),
                            cell,
                            "ray {k} (wrap {wrap}): hit cells differ, t {} vs {t}",
                            f.t
                        );
                        assert!(
                            (f.t - t).abs() < T_TOL_M,
                            "ray {k} (wrap {wrap}): t {} vs {t}",
                            f.t
                        );
                    }
                    (Some(f), _) if !wrap && !interior(f.point) => {
                        // Past the edge of a non-periodic field: the mean plane, where
                        // marching sees the edge samples continued.
                        misses += 1;
                        assert_eq!(f.height_m, pyr.mean_m, "ray {k}: outside hit off the plane");
                    }
                    (None, None) => misses += 1,
                    (f, s) => panic!("ray {k} (wrap {wrap}): quadtree {f:?}, marching {s:?}"),
                }
            }
            assert!(
                hits > RAYS as usize / 2,
                "wrap {wrap}: only {hits} hits ({misses} misses)"
            );
        }
    }

    #[test]
    fn a_ray_aimed_at_a_point_of_a_cosine_hits_at_its_height() {
        // h = A cos(k x), 256 samples over one 64 m wavelength (0.25 m apart).
        const N: usize = 256;
        const L_M: f64 = 64.0;
        const A_M: f64 = 1.0;
        // Bilinear interpolation of the cosine errs by at most A·(k·dx)²/8 = 7.5e-5 m.
        const HEIGHT_TOL_M: f64 = 2e-4;
        const POSITION_TOL_M: f64 = 2e-3;
        let k = std::f64::consts::TAU / L_M;
        let spec = GridSpec::new(N, N, L_M, L_M);
        let grid = Grid::new(
            spec,
            (0..N * N)
                .map(|s| (A_M * (k * spec.x_m(s % N)).cos()) as f32)
                .collect(),
        );
        let pyr = pyramid(&grid, true);
        let tracer = Tracer::new(&pyr, Lod { angle_rad: 0.0 });
        for (m, x) in [3.3, 17.9, 30.1, 41.7, 57.0].into_iter().enumerate() {
            let y = 10.0 + 7.0 * m as f64;
            let target = [x, y, A_M * (k * x).cos()];
            let origin = [x - 6.0, y + 2.0, 12.0];
            let d = unit([0, 1, 2].map(|c| target[c] - origin[c]));
            let hit = tracer
                .trace(&Ray { origin, dir: d })
                .expect("a ray aimed at the sea hits");
            let analytic = A_M * (k * hit.point[0]).cos();
            assert!(
                (hit.height_m - analytic).abs() < HEIGHT_TOL_M,
                "x = {x}: hit height {} vs A cos(k x) = {analytic}",
                hit.height_m
            );
            let miss = (0..3)
                .map(|c| (hit.point[c] - target[c]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                miss < POSITION_TOL_M,
                "x = {x}: hit {:?}, {miss} m from the aimed point",
                hit.point
            );
            // The slope there: −A k sin(k x), by interpolated central differences.
            let slope = -A_M * k * (k * hit.point[0]).sin();
            assert!(
                (hit.slope[0] - slope).abs() < 1e-3,
                "x = {x}: slope {} vs {slope}",
                hit.slope[0]
            );
        }
    }

    #[test]
    fn patch_roots_solve_the_quadratic() {
        // A saddle h = u·v over the unit cell; a ray along u = v at z = 1 − s.
        let c = [[0.0; 3], [0.0; 3], [0.0; 3], [1.0, 0.0, 0.0]];
        let s = patch_root(c, [0.0, 0.0, 1.0], [1.0, 1.0, -1.0], 1.0).expect("crosses");
        // u² = 1 − u  ⇒  u = (√5 − 1)/2.
        assert!((s - (5f64.sqrt() - 1.0) / 2.0).abs() < 1e-12, "s = {s}");
        // Starting below: a hit at once. Passing above: none.
        assert_eq!(
            patch_root(c, [0.5, 0.5, 0.1], [1.0, 0.0, 0.0], 0.5),
            Some(0.0)
        );
        assert_eq!(patch_root(c, [0.0, 0.0, 2.0], [1.0, 1.0, 0.0], 1.0), None);
    }

    #[test]
    fn the_low_pass_flattens_the_far_sea_to_its_mean() {
        let grid = rough_field(64, 64.0);
        let pyr = pyramid(&grid, true);
        let tracer = Tracer::new(&pyr, Lod { angle_rad: 0.01 });
        // A grazing ray from 5 m comes down to the crests (~2 m) after ~1500 m, where its
        // footprint, 0.01·t/√0.01 = 150 m, is past the 64 m tile (λ > 7): the mean plane.
        let d = unit([1.0, 0.3, -0.002]);
        let hit = tracer
            .trace(&Ray {
                origin: [0.0, 0.0, 5.0],
                dir: d,
            })
            .expect("hits");
        assert_eq!(hit.height_m, pyr.mean_m);
        assert!((hit.t - (5.0 - pyr.mean_m) / -d[2]).abs() < 1e-9);
        // A steep ray close by sees the full-resolution surface.
        let near = Ray {
            origin: [10.0, 10.0, 5.0],
            dir: unit([0.2, 0.1, -1.0]),
        };
        let fine = Tracer::new(&pyr, Lod { angle_rad: 0.0 })
            .trace(&near)
            .expect("hits");
        let lod = tracer.trace(&near).expect("hits");
        assert_eq!(
            fine, lod,
            "a 5 m footprint of 1 mrad is far below a 1 m cell"
        );
    }
}
