//! The local approach along the contact line: the point-to-line transition
//! of the Weber–Banaschek term.
//!
//! [`crate::element::weber_banaschek`] gives each slice the approach of a
//! plane-strain strip, i.e. of an infinitely long line loaded everywhere
//! with the slice's own line load q_i. A contact shorter than the line (a
//! crowned flank at light load: an ellipse over a few slices) or loaded
//! unevenly along it has neighbours that carry less, or nothing. The
//! difference q(y) − q_i along the line acts on slice i through the
//! half-space's local field: the approach of the surface point at the
//! slice's centre relative to the point at depth h below it, under a normal
//! point force P at distance y along the surface (Boussinesq, e.g. Johnson,
//! Contact Mechanics, §3.2: u_z(r, z) = P (1 + ν)/(2πE) [2(1 − ν)/R + z²/R³],
//! R = √(r² + z²)):
//!
//!   Δ(y; h) = (1 + ν)/(2πE) · [2(1 − ν)(1/y − 1/R) − h²/R³],  R = √(y² + h²),
//!
//! whose integral along the line has the primitive
//!
//!   ∫ Δ dy = (1 + ν)/(2πE) · P(y),  P(y) = 2(1 − ν)(ln y − asinh(y/h)) − y/√(y² + h²),
//!
//! (P(∞) = 2(1 − ν) ln(h/2) − 1). With q_j spread evenly over slice j, the
//! approach of slice i becomes
//!
//!   w_i = w_2D(q_i) + Σ_{j≠i} q_j ∫_{slice j} Δ − q_i ∫_{line ∖ slice i} Δ,
//!
//! per body (its E, ν and depth h), linear in the forces: the coupling
//! matrix K of [`coupling`], added to the global compliance. It is taken in
//! the symmetric (Galerkin) form, each slice's approach averaged over its
//! own segment: K_ij = (1/(L_i L_j)) ∫_i ∫_j Δ and
//! K_ii = −(1/L_i²) ∫_i ∫_{line ∖ i} Δ, by the second primitive of
//! [`coupling`].
//! Where the slices carry one line load everywhere the two sums cancel
//! exactly (the slices tile the line) and the element is the plane-strain
//! strip as before. The line is the pair's potential contact line, from its
//! first slice's start to its last slice's end: beyond it the line leaves
//! the flank (toe, heel, tip or root) and there is no material to couple, so
//! a slice there keeps the plane-strain value (our choice: a free edge is
//! softer than the half-space, which neither model captures).
//!
//! K's rows, weighted by the slice lengths, sum to zero over a tiled line,
//! and K stiffens uneven loads (Fᵀ K F ≤ 0, tested), as a finite contact is
//! stiffer than the infinite line the strip assumes. Between neighbouring
//! slices K is positive; beyond about twice the depth Δ turns negative
//! (−ν(1 + ν)h²/(2πE y³) far away: the material there is stretched between
//! the surface and depth h), so the line contacts' secants are floored at
//! their rows' Σ_{j≠i} |K_ij| ([`crate::element::weber_banaschek`]). The
//! kernel treats each slice's load as a line (no width): at distances of a
//! slice length it is exact to O((b/L)²), b the Hertz half-width. A slice
//! shorter than [`SHORT`] of its pair's widest (a band clipped at a face
//! end) is left out of K: for L of the order of b the line kernel no longer
//! holds (its K_ii grows like ln(1/L)/L, past the strip's own approach).

use geometry::Material;

/// A slice whose band is narrower than this share of its pair's widest is
/// left out of the coupling (see the module doc).
pub const SHORT: f64 = 0.25;

/// A slice on its pair's contact line: its segment [start, end] along the
/// line (m), the two bodies' reference depths h at it (m), and whether it
/// is short (left out of the coupling, [`SHORT`]).
#[derive(Debug, Clone, Copy)]
pub struct LineSegment {
    pub start: f64,
    pub end: f64,
    pub h: [f64; 2],
    pub short: bool,
}

impl LineSegment {
    fn length(&self) -> f64 {
        self.end - self.start
    }
}

/// The primitive P(y) of the module doc (without the factor (1 + ν)/(2πE)),
/// y > 0; P(∞) = 2(1 − ν) ln(h/2) − 1.
fn primitive(y: f64, h: f64, nu: f64) -> f64 {
    if y.is_infinite() {
        return 2.0 * (1.0 - nu) * (0.5 * h).ln() - 1.0;
    }
    2.0 * (1.0 - nu) * (y.ln() - (y / h).asinh()) - y / (y * y + h * h).sqrt()
}

/// ∫_a^b Δ(y; h) dy (m/N per unit line load), 0 < a ≤ b ≤ ∞: the approach
/// at depth h of a body of material `m` under a unit line load along [a, b]
/// at distance a..b from the point (module doc).
pub fn kernel_integral(a: f64, b: f64, h: f64, m: Material) -> f64 {
    if b <= a {
        return 0.0;
    }
    let nu = m.poisson_ratio;
    (1.0 + nu) / (2.0 * std::f64::consts::PI * m.youngs_modulus_pa)
        * (primitive(b, h, nu) - primitive(a, h, nu))
}

/// The kernel Δ(y; h) itself (m/N per unit force), y > 0.
pub fn kernel(y: f64, h: f64, m: Material) -> f64 {
    let nu = m.poisson_ratio;
    let r = (y * y + h * h).sqrt();
    (1.0 + nu) / (2.0 * std::f64::consts::PI * m.youngs_modulus_pa)
        * (2.0 * (1.0 - nu) * (1.0 / y - 1.0 / r) - h * h / (r * r * r))
}

/// The second primitive Q(y) = ∫ P dy (y ≥ 0, Q(0) = (1 − 2ν) h):
/// Q(y) = 2(1 − ν)(y ln y − y − y asinh(y/h) + √(y² + h²)) − √(y² + h²).
fn second_primitive(y: f64, h: f64, nu: f64) -> f64 {
    let r = (y * y + h * h).sqrt();
    let ylny = if y > 0.0 { y * y.ln() } else { 0.0 };
    2.0 * (1.0 - nu) * (ylny - y - y * (y / h).asinh() + r) - r
}

/// The coupling matrix K (row-major n × n, m/N) of one contact line's
/// slices `segs` (ordered along the line, not overlapping), in the
/// symmetric (Galerkin) form: each slice's approach averaged over its own
/// segment, K_ij = (1/(L_i L_j)) ∫_i ∫_j Δ, K_ii = −(1/L_i²) ∫_i ∫_{line ∖ i} Δ,
/// summed over the two `bodies`, each with one depth along the line (the
/// mean of its coupled slices' depths: h varies by a few per cent along a
/// contact line, and one depth keeps Σ_j K_ij L_j = 0 exact). Short slices
/// have zero rows and columns. Every integral is a sum of second
/// primitives Q at distances between the segments' ends, each evaluated
/// once.
pub fn coupling(segs: &[LineSegment], bodies: [Material; 2]) -> Vec<f64> {
    let n = segs.len();
    let mut k = vec![0.0; n * n];
    let coupled: Vec<usize> = (0..n)
        .filter(|&i| segs[i].length() > 0.0 && !segs[i].short)
        .collect();
    if coupled.is_empty() {
        return k;
    }
    // The segments' ends along the line, once each (a slice's start is
    // usually its neighbour's end), with the line's own ends.
    let mut ends: Vec<f64> = segs.iter().flat_map(|s| [s.start, s.end]).collect();
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    let at = |y: f64| ends.partition_point(|&e| e < y);
    let idx: Vec<[usize; 2]> = segs.iter().map(|s| [at(s.start), at(s.end)]).collect();
    let (first, last) = (0, ends.len() - 1);
    let m = ends.len();
    for (b, &mat) in bodies.iter().enumerate() {
        let h = coupled.iter().map(|&i| segs[i].h[b]).sum::<f64>() / coupled.len() as f64;
        let nu = mat.poisson_ratio;
        let c = (1.0 + nu) / (2.0 * std::f64::consts::PI * mat.youngs_modulus_pa);
        // Q between every two ends (upper triangle; distances ≥ 0).
        let mut q = vec![0.0; m * m];
        for a in 0..m {
            for e in a..m {
                q[a * m + e] = second_primitive(ends[e] - ends[a], h, nu);
            }
        }
        let qq = |a: usize, e: usize| q[a.min(e) * m + a.max(e)];
        // ∫_[a1,e1] ∫_[a2,e2] Δ(y′ − y) dy′ dy for e1 ≤ a2 (end indices):
        // Q(e2 − a1) − Q(e2 − e1) − Q(a2 − a1) + Q(a2 − e1).
        let pair = |[a1, e1]: [usize; 2], [a2, e2]: [usize; 2]| {
            c * (qq(a1, e2) - qq(e1, e2) - qq(a1, a2) + qq(e1, a2))
        };
        for (x, &i) in coupled.iter().enumerate() {
            let li = segs[i].length();
            let own = idx[i];
            let beyond = pair([first, own[0]], own) + pair(own, [own[1], last]);
            k[i * n + i] -= beyond / (li * li);
            for &j in &coupled[x + 1..] {
                let v = pair(own, idx[j]) / (li * segs[j].length());
                k[i * n + j] += v;
                k[j * n + i] += v;
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: Material = Material::STEEL;

    #[test]
    fn second_primitive_differentiates_to_the_primitive() {
        let (h, nu) = (3e-3, STEEL.poisson_ratio);
        for y in [1e-4, 1e-3, 5e-3, 2e-2] {
            let d = 1e-4 * y;
            let numeric =
                (second_primitive(y + d, h, nu) - second_primitive(y - d, h, nu)) / (2.0 * d);
            let exact = primitive(y, h, nu);
            assert!(
                (numeric - exact).abs() < 1e-6 * exact.abs().max(1.0),
                "y = {y}: {numeric} vs {exact}"
            );
        }
        assert!((second_primitive(0.0, h, nu) - (1.0 - 2.0 * nu) * h).abs() < 1e-15);
    }

    #[test]
    fn primitive_differentiates_to_the_boussinesq_kernel() {
        let h = 3e-3;
        for y in [1e-4, 1e-3, 5e-3, 2e-2] {
            let d = 1e-4 * y;
            let numeric = (kernel_integral(y - d, y + d, h, STEEL)) / (2.0 * d);
            let exact = kernel(y, h, STEEL);
            assert!(
                (numeric / exact - 1.0).abs() < 1e-6,
                "y = {y}: {numeric} vs {exact}"
            );
        }
        // The tail: ∫_a^∞ against a long finite integral.
        let a = 1e-3;
        let tail = kernel_integral(a, f64::INFINITY, h, STEEL);
        let long = kernel_integral(a, 1e3, h, STEEL);
        assert!((tail / long - 1.0).abs() < 1e-9, "{tail} {long}");
    }

    fn tiled(lengths: &[f64], h: impl Fn(usize) -> [f64; 2]) -> Vec<LineSegment> {
        let mut y = 0.0;
        lengths
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                let s = LineSegment {
                    start: y,
                    end: y + l,
                    h: h(i),
                    short: false,
                };
                y += l;
                s
            })
            .collect()
    }

    #[test]
    fn an_evenly_loaded_line_keeps_the_plane_strain_strip() {
        // Slices of unequal lengths tiling a line, one depth per body:
        // K F = 0 for F_j = q L_j (the two sums of the module doc cancel).
        let lengths = [0.3e-3, 0.9e-3, 0.9e-3, 0.8e-3, 1.0e-3, 0.9e-3, 0.5e-3];
        let segs = tiled(&lengths, |_| [3e-3, 4e-3]);
        let k = coupling(&segs, [STEEL, STEEL]);
        let n = segs.len();
        let q = 5e5;
        for i in 0..n {
            let w: f64 = (0..n).map(|j| k[i * n + j] * q * lengths[j]).sum();
            let d = k[i * n + i] * q * lengths[i];
            assert!(
                d < 0.0 && w.abs() < 1e-9 * d.abs(),
                "slice {i}: {w} against {d}"
            );
        }
    }

    /// The approach, averaged along the strip's centre line, of a strip of
    /// length `l` and Hertz half-width `b` under line load q, to depth h:
    /// Boussinesq's field of the 3D pressure p = (2q/(πb)) √(1 − x²/b²)
    /// over |y| ≤ l/2 integrated directly (the surface term's y-integral in
    /// closed form, the rest by Gauss–Legendre on x = b sin t and along y).
    fn strip_3d(q: f64, b: f64, l: f64, h: f64, m: Material) -> f64 {
        let nu = m.poisson_ratio;
        let c = (1.0 + nu) / (2.0 * std::f64::consts::PI * m.youngs_modulus_pa);
        let (nt, ny) = (400, 200);
        let gl = |n: usize| -> Vec<(f64, f64)> {
            // Midpoint rule on a cosine-graded grid is enough at these counts.
            (0..n)
                .map(|k| {
                    let (a, e) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                    ((a + e) / 2.0, e - a)
                })
                .collect()
        };
        let p0 = 2.0 * q / (std::f64::consts::PI * b);
        let mut w = 0.0;
        for &(u0, du0) in &gl(ny) {
            let y0 = (u0 - 0.5) * l;
            for &(ut, dut) in &gl(nt) {
                // x = b sin t, t ∈ (−π/2, π/2): p dx = p0 b cos² t dt.
                let t = (ut - 0.5) * std::f64::consts::PI;
                let x = b * t.sin();
                let weight = p0 * b * t.cos().powi(2) * dut * std::f64::consts::PI;
                let ax = x.abs().max(1e-300);
                let surface = 2.0
                    * (1.0 - nu)
                    * (((0.5 * l - y0) / ax).asinh() + ((0.5 * l + y0) / ax).asinh());
                // The depth term, smooth: midpoint along y.
                let mut deep = 0.0;
                let nd = 200;
                for kd in 0..nd {
                    let y = -0.5 * l + (kd as f64 + 0.5) * l / nd as f64;
                    let r = (x * x + (y - y0) * (y - y0) + h * h).sqrt();
                    deep += (2.0 * (1.0 - nu) / r + h * h / (r * r * r)) * l / nd as f64;
                }
                w += c * (surface - deep) * weight * du0;
            }
        }
        w
    }

    #[test]
    fn a_lone_strip_is_the_plane_strain_strip_less_its_missing_neighbours() {
        // One slice loaded on an otherwise unloaded line: the element's
        // local approach w_2D(q) + K_ii F against Boussinesq's 3D field of
        // the finite strip, for strips from a fifth of h to ten times h.
        let (h, rho) = (3e-3, 0.01);
        let e_star = crate::element::weber_banaschek::contact_modulus(STEEL, STEEL);
        for (l, q) in [
            (0.6e-3, 2e5),
            (1.0e-3, 5e5),
            (3e-3, 5e5),
            (10e-3, 1e6),
            (30e-3, 1e6),
        ] {
            let b = crate::element::weber_banaschek::half_width(q, rho, e_star);
            assert!(b < 0.25 * l);
            let w2d = crate::element::weber_banaschek::body_approach(q, b, h, STEEL);
            let seg = [
                LineSegment {
                    start: -1.0,
                    end: -0.5 * l,
                    h: [h; 2],
                    short: false,
                },
                LineSegment {
                    start: -0.5 * l,
                    end: 0.5 * l,
                    h: [h; 2],
                    short: false,
                },
                LineSegment {
                    start: 0.5 * l,
                    end: 1.0,
                    h: [h; 2],
                    short: false,
                },
            ];
            let k = coupling(
                &seg,
                [
                    STEEL,
                    Material {
                        youngs_modulus_pa: f64::INFINITY,
                        ..STEEL
                    },
                ],
            );
            let element = w2d + k[4] * q * l;
            let direct = strip_3d(q, b, l, h, STEEL);
            let rel = element / direct - 1.0;
            eprintln!("l/h = {:.2}: plane strain {w2d:.4e}, element {element:.4e}, 3D {direct:.4e} ({:+.2} %)", l / h, 100.0 * rel);
            // The line kernel's error, O((b/l)²) (module doc), plus the
            // quadrature's; the plane-strain strip alone is far off.
            assert!(
                rel.abs() < 0.005 + (b / l).powi(2),
                "l = {l}: {element} against {direct}"
            );
            assert!(element < w2d && (w2d - direct).abs() > 5.0 * (element - direct).abs());
        }
    }

    #[test]
    fn coupling_stiffens_uneven_loads_only() {
        // Fᵀ K F ≤ 0 for loads of either sign (the kernel's far tail is
        // negative, so this is checked, not implied by the row sums).
        let segs: Vec<_> = (0..12)
            .map(|i| LineSegment {
                start: i as f64 * 0.9e-3,
                end: (i + 1) as f64 * 0.9e-3,
                h: [3e-3, 4e-3],
                short: false,
            })
            .collect();
        let k = coupling(&segs, [STEEL, STEEL]);
        let n = segs.len();
        let mut seed = 7u64;
        for _ in 0..50 {
            let f: Vec<f64> = (0..n)
                .map(|_| {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
                })
                .collect();
            let e: f64 = (0..n)
                .map(|i| (0..n).map(|j| f[i] * k[i * n + j] * f[j]).sum::<f64>())
                .sum();
            let scale: f64 = (0..n).map(|i| k[i * n + i].abs() * f[i] * f[i]).sum();
            assert!(e <= 1e-9 * scale, "{e} {scale}");
        }
    }
}
