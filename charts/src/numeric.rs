//! The numerical helpers of the plots, public and tested on their own:
//! 1-2-5 ticks and contour levels, equal-aspect axis ranges, and marching
//! squares on a structured curvilinear flank grid.

use crate::FlankMap;

/// Ticks at "nice" values (steps of 1, 2 or 5 × 10^k) inside `[lo, hi]`.
///
/// The step is the smallest nice step not smaller than `(hi - lo) / n`, so
/// there are at most `n + 1` ticks. The ticks are equally spaced, sorted
/// ascending and all lie within `[min(lo, hi), max(lo, hi)]`. A degenerate
/// range (`lo == hi`) gives `[lo]`; non-finite bounds give no ticks.
pub fn nice_ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if !lo.is_finite() || !hi.is_finite() {
        return Vec::new();
    }
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    if hi == lo {
        return vec![lo];
    }
    let n = n.max(1);
    let step = nice_step((hi - lo) / n as f64);
    if !(step.is_finite() && step > 0.0) {
        return vec![lo];
    }
    let k0 = (lo / step).ceil();
    let k1 = (hi / step).floor();
    if !(k0.is_finite() && k1.is_finite()) || k1 < k0 {
        return Vec::new();
    }
    let count = (k1 - k0) as i64;
    if count > 10 * (n as i64 + 1) {
        // only possible when |lo|/step exceeds f64 integer precision
        return vec![lo, hi];
    }
    let mut ticks: Vec<f64> = Vec::with_capacity(count as usize + 1);
    for j in 0..=count {
        let mut t = (k0 + j as f64) * step;
        // rounding of k*step may leave the range by an ulp: snap back
        t = t.clamp(lo, hi);
        if t == 0.0 {
            t = 0.0; // no negative zero
        }
        if ticks.last().is_none_or(|&p| t > p) {
            ticks.push(t);
        }
    }
    ticks
}

/// Smallest of {1, 2, 5, 10} × 10^k not below `raw` (> 0).
pub(crate) fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return f64::NAN;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let s = if f <= 1.0 + 1e-12 {
        1.0
    } else if f <= 2.0 + 1e-12 {
        2.0
    } else if f <= 5.0 + 1e-12 {
        5.0
    } else {
        10.0
    };
    s * mag
}

/// Axis ranges with the same length per pixel in x and y.
///
/// `xs` and `ys` are the (lo, hi) data ranges that must be visible; the
/// narrower one (in data units per pixel) is widened symmetrically about its
/// centre so that `(x_hi - x_lo) / width_px == (y_hi - y_lo) / height_px`.
/// `width_px`/`height_px` are the pixel spans the ranges are mapped onto
/// (values below 1 are treated as 1). Reversed bounds are swapped; a range
/// that is degenerate in both directions gets a span of 1 data unit in the
/// direction with fewer pixels per unit; non-finite bounds are replaced by 0..1.
pub fn equal_aspect_ranges(
    xs: (f64, f64),
    ys: (f64, f64),
    width_px: u32,
    height_px: u32,
) -> ((f64, f64), (f64, f64)) {
    let sane = |r: (f64, f64)| {
        if r.0.is_finite() && r.1.is_finite() {
            (r.0.min(r.1), r.0.max(r.1))
        } else {
            (0.0, 1.0)
        }
    };
    let (x0, x1) = sane(xs);
    let (y0, y1) = sane(ys);
    let w = width_px.max(1) as f64;
    let h = height_px.max(1) as f64;
    let mut scale = ((x1 - x0) / w).max((y1 - y0) / h); // data units per pixel
    if !(scale.is_finite() && scale > 0.0) {
        scale = 1.0 / w.min(h);
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hx, hy) = (0.5 * scale * w, 0.5 * scale * h);
    // keep the given bounds exactly when that direction is the binding one
    let xr = if (x1 - x0) / w >= scale {
        (x0, x1)
    } else {
        (cx - hx, cx + hx)
    };
    let yr = if (y1 - y0) / h >= scale {
        (y0, y1)
    } else {
        (cy - hy, cy + hy)
    };
    (xr, yr)
}

/// Iso-line of `grid.value` at `level`, by marching squares.
///
/// Returns the line as segments between points (x, y) on cell edges, found by
/// linear interpolation of the value along each edge. Every cell edge is
/// interpolated in one fixed orientation, so the end points shared by
/// neighbouring cells are bitwise equal. A node counts as "above" when
/// `value >= level`; ambiguous (saddle) cells are resolved with the mean of
/// the four corner values. Cells with a non-finite node are skipped; an
/// inconsistent grid gives no segments.
pub fn iso_segments(grid: &FlankMap, level: f64) -> Vec<((f64, f64), (f64, f64))> {
    let mut out = Vec::new();
    if !grid_is_consistent(grid) || !level.is_finite() {
        return out;
    }
    let np = grid.n_profile;
    let idx = |i: usize, k: usize| i * np + k;
    let node_ok =
        |j: usize| grid.x[j].is_finite() && grid.y[j].is_finite() && grid.value[j].is_finite();
    // crossing point of the edge a -> b (a, b node indices), if any
    let cross = |a: usize, b: usize| -> Option<(f64, f64)> {
        let (va, vb) = (grid.value[a], grid.value[b]);
        if (va >= level) == (vb >= level) {
            return None;
        }
        let t = (level - va) / (vb - va);
        Some((
            grid.x[a] + t * (grid.x[b] - grid.x[a]),
            grid.y[a] + t * (grid.y[b] - grid.y[a]),
        ))
    };
    for i in 0..grid.n_face - 1 {
        for k in 0..np - 1 {
            // corners counter-clockwise in (i, k): c0 (i,k), c1 (i+1,k), c2 (i+1,k+1), c3 (i,k+1)
            let c = [idx(i, k), idx(i + 1, k), idx(i + 1, k + 1), idx(i, k + 1)];
            if !c.iter().all(|&j| node_ok(j)) {
                continue;
            }
            // edges e0 = c0-c1, e1 = c1-c2, e2 = c3-c2, e3 = c0-c3 (canonical orientation:
            // from the lower to the higher node index)
            let e = [
                cross(c[0], c[1]),
                cross(c[1], c[2]),
                cross(c[3], c[2]),
                cross(c[0], c[3]),
            ];
            let hits: Vec<(usize, (f64, f64))> = e
                .iter()
                .enumerate()
                .filter_map(|(j, p)| p.map(|p| (j, p)))
                .collect();
            match hits.len() {
                2 => out.push((hits[0].1, hits[1].1)),
                4 => {
                    let (p0, p1, p2, p3) = (hits[0].1, hits[1].1, hits[2].1, hits[3].1);
                    let mean = c.iter().map(|&j| grid.value[j]).sum::<f64>() / 4.0;
                    let c0_above = grid.value[c[0]] >= level;
                    if (mean >= level) == c0_above {
                        // c0 and c2 are connected through the centre: cut off c1 and c3
                        out.push((p0, p1));
                        out.push((p2, p3));
                    } else {
                        // cut off c0 and c2
                        out.push((p3, p0));
                        out.push((p1, p2));
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// A straight segment between two points (x, y).
pub(crate) type Segment = ((f64, f64), (f64, f64));

pub(crate) fn grid_is_consistent(g: &FlankMap) -> bool {
    let n = g.n_face.checked_mul(g.n_profile);
    g.n_face >= 2
        && g.n_profile >= 2
        && n.is_some_and(|n| g.x.len() == n && g.y.len() == n && g.value.len() == n)
}
