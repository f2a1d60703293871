//! The choppy resampling of one row with AVX2: the sixteen segments of the row in two
//! vectors of eight lanes; a cell's corner pairs (λDx, λDy) loaded 128 bits at a time and
//! transposed, the heights gathered. Every lane performs the scalar kernel's operations in the same order, so the bits are
//! the scalar kernel's.

use std::arch::x86_64::*;

use super::{
    CHOPPY_ITERATIONS, FIXED_POINT_CONVERGED, LANES, NEWTON_CONVERGED, NEWTON_MIN_DET,
    NEWTON_RESIDUAL, Table, segment_length, wrap,
};

/// The constants of a row.
#[derive(Clone, Copy)]
struct Grid {
    nx: __m256i,
    ny: __m256i,
    /// nx + 1: the padded table's row length.
    w: __m256i,
    d: *const i64,
    h: *const f32,
    w_usize: usize,
    nx_i: i32,
    ny_i: i32,
}

/// The row `j` of the resampled heights.
///
/// # Safety
/// The processor must have AVX2; the padded table has at most `i32::MAX` points.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn row(t: &Table, j: usize, row: &mut [f32]) {
    // SAFETY: the caller guarantees AVX2; the gathers and stores address elements
    // within the tables (indices wrapped into the grid).
    unsafe {
        let nx = t.nx;
        let seg = segment_length(nx);
        assert!(row.len() == nx && t.d.len() == (nx + 1) * (t.ny + 1) && t.h.len() == nx * t.ny);
        let g = Grid {
            nx: _mm256_set1_epi32(nx as i32),
            ny: _mm256_set1_epi32(t.ny as i32),
            w: _mm256_set1_epi32(nx as i32 + 1),
            d: t.d.as_ptr().cast::<i64>(),
            h: t.h.as_ptr(),
            w_usize: nx + 1,
            nx_i: nx as i32,
            ny_i: t.ny as i32,
        };
        let jv = _mm256_set1_epi32(j as i32);
        let row_start = _mm256_set1_epi32((j * (nx + 1)) as i32);
        let lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        let seg_v = _mm256_set1_epi32(seg as i32);
        // The first point of the segments of lanes 0–7 and 8–15.
        let first = [
            _mm256_mullo_epi32(lane, seg_v),
            _mm256_mullo_epi32(_mm256_add_epi32(lane, _mm256_set1_epi32(8)), seg_v),
        ];
        let last = _mm256_set1_epi32(nx as i32 - 1);
        let zero = _mm256_setzero_ps();
        // Two vectors of lanes, kept in registers (by value, never indexed).
        let mut a = Lanes {
            i: first[0],
            e: [zero; 2],
            slope: [zero; 2],
            done: zero,
        };
        let mut b = Lanes { i: first[1], ..a };
        let mut heights = [0.0f32; LANES];
        for k in 0..seg {
            let kv = _mm256_set1_epi32(k as i32);
            a = start(
                &g,
                a,
                _mm256_add_epi32(first[0], kv),
                last,
                row_start,
                k == 0,
            );
            b = start(
                &g,
                b,
                _mm256_add_epi32(first[1], kv),
                last,
                row_start,
                k == 0,
            );
            for _ in 0..CHOPPY_ITERATIONS {
                if _mm256_movemask_ps(_mm256_and_ps(a.done, b.done)) == 0xff {
                    break;
                }
                a = advance(&g, jv, a);
                b = advance(&g, jv, b);
            }
            let ha = height(&g, a.i, jv, a.e[0], a.e[1]);
            let hb = height(&g, b.i, jv, b.e[0], b.e[1]);
            _mm256_storeu_ps(heights.as_mut_ptr(), ha);
            _mm256_storeu_ps(heights.as_mut_ptr().add(8), hb);
            for (l, &h) in heights.iter().enumerate() {
                if let Some(out) = row.get_mut(l * seg + k) {
                    *out = h;
                }
            }
        }
    }
}

/// Eight lanes of a row's solve: each one's point, x0 − x, the slope of the last step and
/// whether the point is solved.
#[derive(Clone, Copy)]
struct Lanes {
    i: __m256i,
    e: [__m256; 2],
    slope: [__m256; 2],
    done: __m256,
}

/// The lanes at their next points `i` (lanes past the row's end `last`: done from the
/// start, their index kept in the grid), each starting from −λD there on the first point,
/// else from the last solution moved along its slope.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn start(
    g: &Grid,
    lanes: Lanes,
    i: __m256i,
    last: __m256i,
    row_start: __m256i,
    first: bool,
) -> Lanes {
    // SAFETY: the caller guarantees AVX2; the gathered points are on the row.
    unsafe {
        let past = _mm256_cmpgt_epi32(i, last);
        let i = _mm256_andnot_si256(past, i);
        let e = if first {
            let sign = _mm256_set1_ps(-0.0);
            let [u, v] = pairs(g.d, _mm256_add_epi32(row_start, i));
            [_mm256_xor_ps(u, sign), _mm256_xor_ps(v, sign)]
        } else {
            [
                _mm256_add_ps(lanes.e[0], lanes.slope[0]),
                _mm256_add_ps(lanes.e[1], lanes.slope[1]),
            ]
        };
        Lanes {
            i,
            e,
            slope: lanes.slope,
            done: _mm256_castsi256_ps(past),
        }
    }
}

/// One step in the lanes not yet done.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn advance(g: &Grid, j: __m256i, l: Lanes) -> Lanes {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let s = step(g, l.i, j, l.e[0], l.e[1]);
        let keep = l.done;
        Lanes {
            i: l.i,
            e: [
                _mm256_blendv_ps(s.e[0], l.e[0], keep),
                _mm256_blendv_ps(s.e[1], l.e[1], keep),
            ],
            slope: [
                _mm256_blendv_ps(s.slope[0], l.slope[0], keep),
                _mm256_blendv_ps(s.slope[1], l.slope[1], keep),
            ],
            done: _mm256_or_ps(keep, s.converged),
        }
    }
}

/// The (λDx, λDy) pairs at the padded table's points `p`, as a vector of x and one of y.
/// Two 64-bit gathers (lanes 0–3, then 4–7) and a shuffle, which puts the gathered lanes in
/// the order 0, 1, 4, 5, 2, 3, 6, 7; the points are gathered in that order so they come
/// out in theirs.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn pairs(d: *const i64, p: __m256i) -> [__m256; 2] {
    // SAFETY: as the caller's.
    unsafe {
        let q = _mm256_permutevar8x32_epi32(p, _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7));
        let lo = _mm256_castsi256_ps(_mm256_i32gather_epi64::<8>(d, _mm256_castsi256_si128(q)));
        let hi = _mm256_castsi256_ps(_mm256_i32gather_epi64::<8>(
            d,
            _mm256_extracti128_si256::<1>(q),
        ));
        [
            _mm256_shuffle_ps::<0b10_00_10_00>(lo, hi),
            _mm256_shuffle_ps::<0b11_01_11_01>(lo, hi),
        ]
    }
}

/// The (λDx, λDy) pairs at the corners p, p + 1, p + w, p + w + 1 of each lane's cell,
/// by corner then axis: per lane two 128-bit loads (a corner pair of each row), then a
/// 4 × 4 transpose in each half of the vectors (lanes 0–3 below, 4–7 above). Faster than
/// gathers where those fetch one element per cycle.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn corners(d: *const f32, w: usize, p: __m256i) -> [[__m256; 2]; 4] {
    // SAFETY: the caller guarantees AVX2 and cells within the padded table: p + w + 1 is
    // in it, so every 128-bit load is.
    unsafe {
        let mut at = [0i32; 8];
        _mm256_storeu_si256(at.as_mut_ptr().cast(), p);
        // Lane a's corner pair on row r below, lane a + 4's above.
        macro_rules! pair {
            ($a:expr, $r:expr) => {
                _mm256_loadu2_m128(
                    d.add(2 * (at[$a + 4] as usize + $r)),
                    d.add(2 * (at[$a] as usize + $r)),
                )
            };
        }
        let mut out = [[_mm256_setzero_ps(); 2]; 4];
        for r in 0..2 {
            let (a, b, c, e) = (
                pair!(0, r * w),
                pair!(1, r * w),
                pair!(2, r * w),
                pair!(3, r * w),
            );
            let (t0, t1) = (_mm256_unpacklo_ps(a, b), _mm256_unpackhi_ps(a, b));
            let (t2, t3) = (_mm256_unpacklo_ps(c, e), _mm256_unpackhi_ps(c, e));
            // The low and the high 64 bits of each 128 of x and y, side by side.
            macro_rules! lo {
                ($x:expr, $y:expr) => {
                    _mm256_castpd_ps(_mm256_unpacklo_pd(
                        _mm256_castps_pd($x),
                        _mm256_castps_pd($y),
                    ))
                };
            }
            macro_rules! hi {
                ($x:expr, $y:expr) => {
                    _mm256_castpd_ps(_mm256_unpackhi_pd(
                        _mm256_castps_pd($x),
                        _mm256_castps_pd($y),
                    ))
                };
            }
            out[2 * r] = [lo!(t0, t2), hi!(t0, t2)];
            out[2 * r + 1] = [lo!(t1, t3), hi!(t1, t3)];
        }
        out
    }
}

/// One step of [`super::step`] in each lane.
struct Step {
    e: [__m256; 2],
    slope: [__m256; 2],
    converged: __m256,
}

/// [`super::Patch`] in each lane.
#[derive(Clone, Copy)]
struct Patch {
    v0: __m256,
    v2: __m256,
    d01: __m256,
    d23: __m256,
    twist: __m256,
}

/// [`super::Newton`] in each lane.
struct Newton {
    f: [__m256; 2],
    norm: __m256,
    det: __m256,
    step: [__m256; 2],
    slope: [__m256; 2],
    newton: __m256,
}

/// [`super::Patch::new`] in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn patch(v0: __m256, v1: __m256, v2: __m256, v3: __m256) -> Patch {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let (d01, d23) = (_mm256_sub_ps(v1, v0), _mm256_sub_ps(v3, v2));
        Patch {
            v0,
            v2,
            d01,
            d23,
            twist: _mm256_sub_ps(d23, d01),
        }
    }
}

/// [`super::Patch::at`] in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn at(p: &Patch, tx: __m256, ty: __m256) -> (__m256, [__m256; 2]) {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let a = _mm256_add_ps(p.v0, _mm256_mul_ps(p.d01, tx));
        let b = _mm256_add_ps(p.v2, _mm256_mul_ps(p.d23, tx));
        let ba = _mm256_sub_ps(b, a);
        (
            _mm256_add_ps(a, _mm256_mul_ps(ba, ty)),
            [_mm256_add_ps(p.d01, _mm256_mul_ps(p.twist, ty)), ba],
        )
    }
}

/// [`super::newton`] in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn newton(p: &[Patch; 2], tx: __m256, ty: __m256, ex: __m256, ey: __m256) -> Newton {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let (vx, gx) = at(&p[0], tx, ty);
        let (vy, gy) = at(&p[1], tx, ty);
        let one = _mm256_set1_ps(1.0);
        let (fx, fy) = (_mm256_add_ps(ex, vx), _mm256_add_ps(ey, vy));
        let (j00, j01, j10, j11) = (
            _mm256_add_ps(one, gx[0]),
            gx[1],
            gy[0],
            _mm256_add_ps(one, gy[1]),
        );
        let det = _mm256_sub_ps(_mm256_mul_ps(j00, j11), _mm256_mul_ps(j01, j10));
        let inv = _mm256_div_ps(one, det);
        Newton {
            f: [fx, fy],
            norm: _mm256_add_ps(
                _mm256_add_ps(_mm256_add_ps(abs(j00), abs(j01)), abs(j10)),
                abs(j11),
            ),
            det,
            step: [
                _mm256_mul_ps(
                    _mm256_sub_ps(_mm256_mul_ps(j11, fx), _mm256_mul_ps(j01, fy)),
                    inv,
                ),
                _mm256_mul_ps(
                    _mm256_sub_ps(_mm256_mul_ps(j00, fy), _mm256_mul_ps(j10, fx)),
                    inv,
                ),
            ],
            slope: [
                _mm256_sub_ps(_mm256_mul_ps(j11, inv), one),
                _mm256_mul_ps(_mm256_xor_ps(j10, _mm256_set1_ps(-0.0)), inv),
            ],
            newton: _mm256_cmp_ps::<_CMP_GE_OQ>(det, _mm256_set1_ps(NEWTON_MIN_DET)),
        }
    }
}

/// [`super::newton_done`] in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn newton_done(p: &[Patch; 2], n: &Newton, tx: __m256, ty: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let [dx, dy] = n.step;
        let short = _mm256_and_ps(below(dx, NEWTON_CONVERGED), below(dy, NEWTON_CONVERGED));
        let inside = _mm256_and_ps(
            in_unit(_mm256_sub_ps(tx, dx)),
            in_unit(_mm256_sub_ps(ty, dy)),
        );
        let residual = _mm256_mul_ps(
            _mm256_add_ps(abs(p[0].twist), abs(p[1].twist)),
            abs(_mm256_mul_ps(dx, dy)),
        );
        let quadratic = _mm256_cmp_ps::<_CMP_LT_OQ>(
            _mm256_mul_ps(residual, n.norm),
            _mm256_mul_ps(_mm256_set1_ps(NEWTON_RESIDUAL), n.det),
        );
        _mm256_or_ps(short, _mm256_and_ps(inside, quadratic))
    }
}

/// [`super::step`] in each lane: both branches computed, the lanes' own chosen.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn step(g: &Grid, i: __m256i, j: __m256i, ex: __m256, ey: __m256) -> Step {
    // SAFETY: the caller guarantees AVX2; `locate` wraps the cell into the grid.
    unsafe {
        let (x0, y0, tx, ty) = locate(g, i, j, ex, ey);
        let p = _mm256_add_epi32(_mm256_mullo_epi32(y0, g.w), x0);
        let v = corners(g.d.cast::<f32>(), g.w_usize, p);
        let patches = [
            patch(v[0][0], v[1][0], v[2][0], v[3][0]),
            patch(v[0][1], v[1][1], v[2][1], v[3][1]),
        ];
        let first = newton(&patches, tx, ty, ex, ey);
        let (ex1, ey1) = (
            _mm256_sub_ps(ex, first.step[0]),
            _mm256_sub_ps(ey, first.step[1]),
        );
        let (ux, uy) = (
            _mm256_sub_ps(tx, first.step[0]),
            _mm256_sub_ps(ty, first.step[1]),
        );
        let second = newton(&patches, ux, uy, ex1, ey1);
        let use_second = _mm256_and_ps(
            _mm256_and_ps(first.newton, second.newton),
            _mm256_and_ps(in_unit(ux), in_unit(uy)),
        );
        let done_first = newton_done(&patches, &first, tx, ty);
        let done_second = newton_done(&patches, &second, ux, uy);
        let fixed_done = _mm256_and_ps(
            below(first.f[0], FIXED_POINT_CONVERGED),
            below(first.f[1], FIXED_POINT_CONVERGED),
        );
        let newton_e = [
            _mm256_blendv_ps(ex1, _mm256_sub_ps(ex1, second.step[0]), use_second),
            _mm256_blendv_ps(ey1, _mm256_sub_ps(ey1, second.step[1]), use_second),
        ];
        let newton_slope = [
            _mm256_blendv_ps(first.slope[0], second.slope[0], use_second),
            _mm256_blendv_ps(first.slope[1], second.slope[1], use_second),
        ];
        let ok = first.newton;
        Step {
            e: [
                _mm256_blendv_ps(_mm256_sub_ps(ex, first.f[0]), newton_e[0], ok),
                _mm256_blendv_ps(_mm256_sub_ps(ey, first.f[1]), newton_e[1], ok),
            ],
            slope: [
                _mm256_and_ps(ok, newton_slope[0]),
                _mm256_and_ps(ok, newton_slope[1]),
            ],
            converged: _mm256_blendv_ps(
                fixed_done,
                _mm256_blendv_ps(done_first, done_second, use_second),
                ok,
            ),
        }
    }
}

/// [`super::locate`] in each lane: the cell's first corner (x0, y0) and the weights.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn locate(
    g: &Grid,
    i: __m256i,
    j: __m256i,
    ex: __m256,
    ey: __m256,
) -> (__m256i, __m256i, __m256, __m256) {
    // SAFETY: the caller guarantees AVX2; the gathers and stores address elements
    // within the tables (indices wrapped into the grid).
    unsafe {
        let (fx, fy) = (_mm256_floor_ps(ex), _mm256_floor_ps(ey));
        let (tx, ty) = (_mm256_sub_ps(ex, fx), _mm256_sub_ps(ey, fy));
        let x0 = wrap_lanes(_mm256_add_epi32(i, _mm256_cvttps_epi32(fx)), g.nx, g.nx_i);
        let y0 = wrap_lanes(_mm256_add_epi32(j, _mm256_cvttps_epi32(fy)), g.ny, g.ny_i);
        (x0, y0, tx, ty)
    }
}

/// [`super::height`] in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn height(g: &Grid, i: __m256i, j: __m256i, ex: __m256, ey: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX2; the gathers and stores address elements
    // within the tables (indices wrapped into the grid).
    unsafe {
        let (x0, y0, tx, ty) = locate(g, i, j, ex, ey);
        let (x1, y1) = (next(x0, g.nx), next(y0, g.ny));
        let (r0, r1) = (_mm256_mullo_epi32(y0, g.nx), _mm256_mullo_epi32(y1, g.nx));
        let v = [
            _mm256_i32gather_ps::<4>(g.h, _mm256_add_epi32(r0, x0)),
            _mm256_i32gather_ps::<4>(g.h, _mm256_add_epi32(r0, x1)),
            _mm256_i32gather_ps::<4>(g.h, _mm256_add_epi32(r1, x0)),
            _mm256_i32gather_ps::<4>(g.h, _mm256_add_epi32(r1, x1)),
        ];
        let a = _mm256_add_ps(v[0], _mm256_mul_ps(_mm256_sub_ps(v[1], v[0]), tx));
        let b = _mm256_add_ps(v[2], _mm256_mul_ps(_mm256_sub_ps(v[3], v[2]), tx));
        _mm256_add_ps(a, _mm256_mul_ps(_mm256_sub_ps(b, a), ty))
    }
}

/// [`wrap`] in each lane: one conditional add or subtract of `n` for indices within one
/// period of the grid, the scalar remainder for the rare lanes farther out.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn wrap_lanes(c: __m256i, n: __m256i, n_i: i32) -> __m256i {
    // SAFETY: the caller guarantees AVX2; the gathers and stores address elements
    // within the tables (indices wrapped into the grid).
    unsafe {
        let zero = _mm256_setzero_si256();
        let top = _mm256_sub_epi32(n, _mm256_set1_epi32(1));
        let below = _mm256_cmpgt_epi32(zero, c);
        let above = _mm256_cmpgt_epi32(c, top);
        let w = _mm256_sub_epi32(
            _mm256_add_epi32(c, _mm256_and_si256(below, n)),
            _mm256_and_si256(above, n),
        );
        let bad = _mm256_or_si256(_mm256_cmpgt_epi32(zero, w), _mm256_cmpgt_epi32(w, top));
        if _mm256_testz_si256(bad, bad) != 0 {
            return w;
        }
        wrap_far(c, n_i)
    }
}

/// c + 1 in each lane, 0 where that is `n`.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn next(c: __m256i, n: __m256i) -> __m256i {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        let c1 = _mm256_add_epi32(c, _mm256_set1_epi32(1));
        _mm256_andnot_si256(_mm256_cmpeq_epi32(c1, n), c1)
    }
}

/// |x| in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn abs(x: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX2.
    unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), x) }
}

/// |x| < limit in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn below(x: __m256, limit: f32) -> __m256 {
    // SAFETY: the caller guarantees AVX2.
    unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(abs(x), _mm256_set1_ps(limit)) }
}

/// 0 ≤ x < 1 in each lane.
#[target_feature(enable = "avx2")]
#[inline]
#[allow(unused_unsafe)]
unsafe fn in_unit(x: __m256) -> __m256 {
    // SAFETY: the caller guarantees AVX2.
    unsafe {
        _mm256_and_ps(
            _mm256_cmp_ps::<_CMP_GE_OQ>(x, _mm256_setzero_ps()),
            _mm256_cmp_ps::<_CMP_LT_OQ>(x, _mm256_set1_ps(1.0)),
        )
    }
}

/// [`wrap`] in each lane, one by one.
#[target_feature(enable = "avx2")]
#[cold]
#[inline(never)]
unsafe fn wrap_far(c: __m256i, n: i32) -> __m256i {
    // SAFETY: the caller guarantees AVX2; the stores and loads address `lanes`.
    unsafe {
        let mut lanes = [0i32; 8];
        _mm256_storeu_si256(lanes.as_mut_ptr().cast(), c);
        for l in lanes.iter_mut() {
            *l = wrap(*l, n);
        }
        _mm256_loadu_si256(lanes.as_ptr().cast())
    }
}
