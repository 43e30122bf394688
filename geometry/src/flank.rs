//! Flanks bounded by the blank, with the pinion's ease-off, evaluated at
//! axial-section coordinates: position, outward normal, principal curvatures.
//!
//! Flank coordinates: L is the cone distance and d the height above the
//! pitch cone, both in the axial section of the member (the plane through the
//! axis), taken at the unmodified (conjugate) flank point. The normalised
//! coordinates are face ξ = (L − R_i)/b (0 toe, 1 heel) and profile
//! η = (d − d_low(L)) / (d_face(L) − d_low(L)) (0 at the fillet limit, 1 at the tip).

use crate::design::{Member, PairData};
use crate::ease_off::EaseOff;
use crate::error::GeometryError;
use crate::generation::{GeneratedFlank, RawPoint, Side};
use crate::Scalar;
use nalgebra::{Const, Matrix2, SVector, Vector2, Vector3};
use num_dual::{hessian, Dual2Vec};
use serde::Serialize;

/// A line d = d0 + slope (L − R_m) + curve (L − R_m)² in the axial section.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Line {
    pub d0: f64,
    pub slope: f64,
    pub curve: f64,
}

impl Line {
    pub fn straight(d0: f64, slope: f64) -> Self {
        Line {
            d0,
            slope,
            curve: 0.0,
        }
    }
    pub fn at<D: Scalar>(&self, l: D, rm: f64) -> D {
        let x = l - rm;
        x * x * self.curve + x * self.slope + self.d0
    }
    /// The parabola through three points (L, d).
    pub fn through(p: [(f64, f64); 3], rm: f64) -> Self {
        let x: Vec<f64> = p.iter().map(|q| q.0 - rm).collect();
        let m = nalgebra::Matrix3::from_fn(|i, j| x[i].powi(j as i32));
        let c = m
            .lu()
            .solve(&Vector3::new(p[0].1, p[1].1, p[2].1))
            .unwrap_or_default();
        Line {
            d0: c[0],
            slope: c[1],
            curve: c[2],
        }
    }
}

/// Blank bounds of one flank in the axial section.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Bounds {
    pub rm: f64,
    pub inner: f64,
    pub outer: f64,
    /// Face cone line.
    pub face: Line,
    /// Root cone line.
    pub root: Line,
    /// Lower limit of the straight-blade flank: where the edge-radius fillet
    /// meets it. [`Bounds::new`] starts from ρ_e (1 − sin α) above the root
    /// line; [`Flank::fit_fillet_limit`] replaces it by the generated junction.
    pub low: Line,
}

impl Bounds {
    pub fn new(pair: &PairData, m: Member, side: Side) -> Self {
        let d = pair.member(m);
        let g = d.pitch_angle;
        let rm = pair.mean_cone_distance;
        let root = Line::straight(-d.mean_dedendum, (d.root_angle - g).tan());
        let fillet = pair.edge_radius * (1.0 - pair.pressure_angle[side.index()].sin());
        Bounds {
            rm,
            inner: pair.inner_cone_distance(),
            outer: pair.outer_cone_distance(),
            face: Line::straight(d.mean_addendum, (d.face_angle - g).tan()),
            root,
            low: Line::straight(root.d0 + fillet, root.slope),
        }
    }
    /// (L, d) from normalised (ξ face, η profile).
    pub fn from_unit(&self, xi: f64, eta: f64) -> (f64, f64) {
        let l = self.inner + xi * (self.outer - self.inner);
        let lo = self.low.at(l, self.rm);
        (l, lo + eta * (self.face.at(l, self.rm) - lo))
    }
    /// Normalised (ξ, η) from (L, d).
    pub fn to_unit<D: Scalar>(&self, l: D, d: D) -> (D, D) {
        let lo = self.low.at(l, self.rm);
        let hi = self.face.at(l, self.rm);
        (
            (l - self.inner) / (self.outer - self.inner),
            (d - lo) / (hi - lo),
        )
    }
    /// True when (L, d) lies on the flank (toe..heel, fillet limit..tip), with tolerance.
    /// Signed distance of (L, d) inside the bounds, m (negative outside):
    /// the smallest of the four margins to toe, heel, lower limit and face.
    pub fn margin(&self, l: f64, d: f64) -> f64 {
        (l - self.inner)
            .min(self.outer - l)
            .min(d - self.low.at(l, self.rm))
            .min(self.face.at(l, self.rm) - d)
    }
    pub fn contains(&self, l: f64, d: f64, tol: f64) -> bool {
        l >= self.inner - tol
            && l <= self.outer + tol
            && d >= self.low.at(l, self.rm) - tol
            && d <= self.face.at(l, self.rm) + tol
    }
}

/// A flank point with everything the analyses need.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct FlankPoint {
    /// Generating parameters (ζ, s).
    pub uv: [f64; 2],
    /// Position in the member frame (tooth 0), modified flank, m.
    pub pos: [f64; 3],
    /// Outward unit normal in the member frame.
    pub normal: [f64; 3],
    /// Axial-section coordinates of the conjugate point (L, d), m.
    pub l: f64,
    pub d: f64,
    /// Pinion rotation at which the conjugate point is on the contact line, rad.
    pub pinion_roll: f64,
    /// Normal deviation from the conjugate flank (positive = material removed), m.
    pub ease_off: f64,
    /// Wheel normal lever |n · (a₂ × r)| at the contact position, m/rad.
    pub wheel_lever: f64,
}

/// Principal curvatures (positive = convex, i.e. bending away from the
/// outward normal) and unit principal directions in the member frame.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Curvature {
    pub k: [f64; 2],
    pub dir: [[f64; 3]; 2],
}

/// A flank of one member: generated surface, blank bounds, modification.
#[derive(Debug, Clone)]
pub struct Flank {
    pub gen: GeneratedFlank,
    pub bounds: Bounds,
    pub ease: Option<EaseOff>,
    /// Roll ratio of the pinion, φ₁ / φ_c.
    pinion_ratio: f64,
    /// Wheel axis in the fixed frame.
    wheel_axis: Vector3<f64>,
}

/// Newton's solution (ζ, s), its last Jacobian ∂(L, d)/∂(ζ, s) and the
/// generated point there.
type NewtonLd = ([f64; 2], Option<Matrix2<f64>>, RawPoint<f64>);

/// The generic modified point: position (member frame), outward normal of the
/// unmodified surface, (L, d), pinion roll, ease-off, wheel lever.
struct Generic<D> {
    pos: [D; 3],
    normal: [D; 3],
    l: D,
    d: D,
    roll: D,
    ease: D,
    lever: D,
}

impl Flank {
    pub fn new(
        gen: GeneratedFlank,
        bounds: Bounds,
        ease: Option<EaseOff>,
        pinion_ratio: f64,
        wheel_axis: Vector3<f64>,
    ) -> Self {
        Flank {
            gen,
            bounds,
            ease,
            pinion_ratio,
            wheel_axis,
        }
    }

    fn generic<D: Scalar>(&self, u: D, v: D) -> Generic<D> {
        self.modified(self.gen.eval(u, v))
    }

    /// The generic modified point of a generated (conjugate) point.
    fn modified<D: Scalar>(&self, raw: RawPoint<D>) -> Generic<D> {
        let (l, d) = self.gen.frame.axial(&raw.pos);
        let roll = raw.crown_roll * self.pinion_ratio;
        let a = self.wheel_axis;
        let r = raw.pos_fixed;
        let n = raw.normal_fixed;
        let axr = [
            r[2] * a[1] - r[1] * a[2],
            r[0] * a[2] - r[2] * a[0],
            r[1] * a[0] - r[0] * a[1],
        ];
        let lever = (n[0] * axr[0] + n[1] * axr[1] + n[2] * axr[2]).abs();
        let ease = match &self.ease {
            Some(e) => {
                let (xi, eta) = self.bounds.to_unit(l, d);
                e.value(xi, eta, roll, lever)
            }
            None => D::zero(),
        };
        let pos = std::array::from_fn(|i| raw.pos[i] - raw.normal[i] * ease);
        Generic {
            pos,
            normal: raw.normal,
            l,
            d,
            roll,
            ease,
            lever,
        }
    }

    /// Evaluates at generating parameters (ζ, s).
    pub fn eval_uv(&self, u: f64, v: f64) -> FlankPoint {
        self.point_of(u, v, self.gen.eval(u, v))
    }

    /// The flank point at (ζ, s) from its generated point `raw`.
    fn point_of(&self, u: f64, v: f64, raw: RawPoint<f64>) -> FlankPoint {
        let g = self.modified(raw);
        FlankPoint {
            uv: [u, v],
            pos: g.pos,
            normal: g.normal,
            l: g.l,
            d: g.d,
            pinion_roll: g.roll,
            ease_off: g.ease,
            wheel_lever: g.lever,
        }
    }

    /// Axial-section coordinates of the conjugate point at (ζ, s).
    pub fn ld(&self, u: f64, v: f64) -> (f64, f64) {
        let raw = self.gen.eval(u, v);
        self.gen.frame.axial(&raw.pos)
    }

    /// Generating parameters of the flank point at (L, d), by Newton.
    pub fn solve_ld(&self, l: f64, d: f64) -> Result<[f64; 2], GeometryError> {
        let (u, v) = self.gen.guess(l, d);
        self.solve_ld_from(l, d, [u, v])
    }

    /// As [`Flank::solve_ld`], starting Newton from `start`.
    ///
    /// The Jacobian ∂(L, d)/∂(ζ, s) is taken by forward differences at the
    /// first iterate and then kept up to date by Broyden's rank-one update
    /// (one flank evaluation per iteration instead of three), taken afresh
    /// whenever an iteration fails to halve the residual. Where that does
    /// not converge (low on the profile, near a fold of the generated
    /// surface), plain Newton with a difference Jacobian at every iterate
    /// is tried. The tolerance on (L, d) is 1e-13 m either way.
    pub fn solve_ld_from(
        &self,
        l: f64,
        d: f64,
        start: [f64; 2],
    ) -> Result<[f64; 2], GeometryError> {
        self.solved_ld(l, d, start).map(|(uv, _)| uv)
    }

    /// As [`Flank::solve_ld_from`], with the generated point at the solution.
    fn solved_ld(
        &self,
        l: f64,
        d: f64,
        start: [f64; 2],
    ) -> Result<([f64; 2], RawPoint<f64>), GeometryError> {
        self.newton_ld(l, d, start, None, true)
            .or_else(|| self.newton_ld(l, d, start, None, false))
            .map(|(uv, _, raw)| (uv, raw))
            .ok_or(GeometryError::NoFlankPoint {
                member: self.gen.member.name(),
                flank: self.gen.side.flank_name(self.gen.member),
                cone_distance_mm: l * 1e3,
                height_mm: d * 1e3,
            })
    }

    /// Newton for (L, d) from `start` with an optional initial Jacobian;
    /// returns the solution, the last Jacobian used and the generated point
    /// there.
    fn newton_ld(
        &self,
        l: f64,
        d: f64,
        start: [f64; 2],
        jac0: Option<Matrix2<f64>>,
        broyden: bool,
    ) -> Option<NewtonLd> {
        let mut x = Vector2::new(start[0], start[1]);
        let h = 1e-7;
        let generated = |x: &Vector2<f64>| {
            let raw = self.gen.eval(x[0], x[1]);
            let (l0, d0) = self.gen.frame.axial(&raw.pos);
            (Vector2::new(l0 - l, d0 - d), raw)
        };
        let residual = |x: &Vector2<f64>| generated(x).0;
        let (mut r, mut raw) = generated(&x);
        let mut jac = jac0;
        let mut last = jac0;
        for _ in 0..60 {
            if r[0].abs() < 1e-13 && r[1].abs() < 1e-13 {
                return Some(([x[0], x[1]], last, raw));
            }
            let j = match jac {
                Some(j) => j,
                None => {
                    let ru = residual(&Vector2::new(x[0] + h, x[1]));
                    let rv = residual(&Vector2::new(x[0], x[1] + h));
                    Matrix2::from_columns(&[(ru - r) / h, (rv - r) / h])
                }
            };
            last = Some(j);
            let step = j.try_inverse()? * r;
            let dx = -step * (0.02 / step.norm()).min(1.0);
            x += dx;
            let r_new;
            (r_new, raw) = generated(&x);
            // Broyden: J ← J + (Δr − J Δx) Δxᵀ / (Δxᵀ Δx).
            jac = (broyden && r_new.norm() < 0.5 * r.norm())
                .then(|| j + (r_new - r - j * dx) * dx.transpose() / dx.dot(&dx));
            r = r_new;
        }
        None
    }

    /// Flank point at (L, d).
    pub fn at(&self, l: f64, d: f64) -> Result<FlankPoint, GeometryError> {
        let (u, v) = self.gen.guess(l, d);
        let ([u, v], raw) = self.solved_ld(l, d, [u, v])?;
        Ok(self.point_of(u, v, raw))
    }

    /// Flank point at normalised (ξ face, η profile).
    pub fn at_unit(&self, xi: f64, eta: f64) -> Result<FlankPoint, GeometryError> {
        let (l, d) = self.bounds.from_unit(xi, eta);
        self.at(l, d)
    }

    /// As [`Flank::at_unit`], Newton started from the generating parameters
    /// `start` of a nearby point and, if given, the Jacobian ∂(L, d)/∂(ζ, s)
    /// there (falling back to the usual start). Returns the point and the
    /// Jacobian to pass to the next nearby evaluation.
    pub fn at_unit_from(
        &self,
        xi: f64,
        eta: f64,
        start: [f64; 2],
        jacobian: Option<Matrix2<f64>>,
    ) -> Result<(FlankPoint, Option<Matrix2<f64>>), GeometryError> {
        let (l, d) = self.bounds.from_unit(xi, eta);
        Ok(match self.newton_ld(l, d, start, jacobian, true) {
            Some((uv, jac, raw)) => (self.point_of(uv[0], uv[1], raw), jac),
            None => (self.at(l, d)?, None),
        })
    }

    /// Spiral angle and normal pressure angle (rad) at (L, d), from the
    /// position and normal alone: with the pitch-cone normal ν and generatrix g
    /// at the point, pressure angle = asin |n·ν| and spiral angle =
    /// angle(n × ν, g), the tooth trace on the cone.
    pub fn spiral_and_pressure_angle(&self, l: f64, d: f64) -> Result<(f64, f64), GeometryError> {
        let p = self.at(l, d)?;
        let (s, c) = self.gen.frame.pitch_angle.sin_cos();
        let pos = Vector3::from(p.pos);
        let e_rho = Vector3::new(pos[0], pos[1], 0.0).normalize();
        let e_ax = Vector3::z();
        let nu = e_rho * c - e_ax * s;
        let gen = e_ax * c + e_rho * s;
        let n = Vector3::from(p.normal);
        let trace = n.cross(&nu).normalize();
        Ok((trace.dot(&gen).abs().acos(), n.dot(&nu).abs().asin()))
    }

    /// Replaces the approximate lower limit by a parabola through the
    /// generated flank–fillet junction at toe, mean and heel.
    pub fn fit_fillet_limit(&mut self) -> Result<(), GeometryError> {
        let b = self.bounds;
        let mut pts = [(0.0, 0.0); 3];
        for (k, l) in [b.inner, b.rm, b.outer].into_iter().enumerate() {
            let s = self.fillet_arc_at(l)?;
            let q = self.gen.eval_fillet(0.0, s);
            pts[k] = self.gen.frame.axial(&q.pos);
        }
        self.bounds.low = Line::through(pts, b.rm);
        Ok(())
    }

    /// Cutter arc length s of the fillet section whose junction with the flank
    /// lies at cone distance `l`.
    ///
    /// A secant iteration on the L of the fillet surface at ψ = 0
    /// ([`GeneratedFlank::eval_fillet`]) comes first. That point's normal is
    /// taken from difference tangents, whose rounding moves the generated
    /// junction by up to a few 1e-11 m in L (and ~1e-10 m in height) from one
    /// s to the next: at the 1e-12 m tolerance the iteration can cycle between
    /// two iterates on either side of the root (±2.7e-12 m at the toe of the
    /// seed001_9x40 pinion's concave flank, ±1.2e-11 m on the seed002_9x37
    /// wheel's convex flank). Where it has not converged after 30 steps, the
    /// same junction is solved as the straight blade's point at the tangency
    /// height with the blade's exact normal ([`GeneratedFlank::junction`]),
    /// whose L is smooth in s, by Newton to the same tolerance.
    pub fn fillet_arc_at(&self, l: f64) -> Result<f64, GeometryError> {
        let lj = |s: f64| {
            let p = self.gen.eval_fillet(0.0, s);
            self.gen.frame.axial(&p.pos).0
        };
        let start = self.solve_ld(l, self.bounds.low.at(l, self.bounds.rm))?[1];
        // s ← s − step(s, f) until |L(s) − l| < 1e-12 m, 30 steps at most.
        let converge = |lj: &dyn Fn(f64) -> f64, step: &dyn Fn(f64, f64) -> f64| {
            let mut s = start;
            for _ in 0..30 {
                let f = lj(s) - l;
                if f.abs() < 1e-12 {
                    return Some(s);
                }
                s -= step(s, f);
            }
            None
        };
        let h = 1e-6;
        if let Some(s) = converge(&lj, &|s, f| f * h / (lj(s + h) - lj(s))) {
            return Ok(s);
        }
        let lj = |s: f64| self.gen.frame.axial(&self.gen.junction(s).pos).0;
        if let Some(s) = converge(&lj, &|s, f| f * 2.0 * h / (lj(s + h) - lj(s - h))) {
            return Ok(s);
        }
        Err(GeometryError::NoFilletJunction {
            member: self.gen.member.name(),
            flank: self.gen.side.flank_name(self.gen.member),
            cone_distance_mm: l * 1e3,
        })
    }

    /// First and second derivatives of the modified position with respect to
    /// (ζ, s), exact (hyper-dual numbers): (r, [r_u, r_v], [r_uu, r_uv, r_vv]).
    pub fn derivatives(&self, u: f64, v: f64) -> ([f64; 3], [[f64; 3]; 2], [[f64; 3]; 3]) {
        type D2 = Dual2Vec<f64, Const<2>>;
        let res = hessian(
            |x: SVector<D2, 2>| self.generic(x[0], x[1]).pos,
            &SVector::from([u, v]),
        );
        let r = std::array::from_fn(|i| res[i].0);
        let d1 = [
            std::array::from_fn(|i| res[i].1[0]),
            std::array::from_fn(|i| res[i].1[1]),
        ];
        let d2 = [
            std::array::from_fn(|i| res[i].2[(0, 0)]),
            std::array::from_fn(|i| res[i].2[(0, 1)]),
            std::array::from_fn(|i| res[i].2[(1, 1)]),
        ];
        (r, d1, d2)
    }

    /// Principal curvatures and directions at (ζ, s) of the modified flank.
    pub fn curvature_uv(&self, u: f64, v: f64) -> Curvature {
        let (_, d1, d2) = self.derivatives(u, v);
        let n_out = Vector3::from(self.eval_uv(u, v).normal);
        curvature_from_derivatives(d1, d2, &n_out)
    }
}

/// Principal curvatures from the first and second derivatives of a
/// parametrisation: shape operator S = I⁻¹ II with the outward normal; the
/// curvature is reported positive for a convex surface (κ = −eig S).
///
/// Where the derivatives are not finite or the parametrisation is singular
/// (no Cholesky factor of I), the curvatures and directions are NaN rather
/// than a panic. A non-finite ease-off (a NaN in a topography grid) was the
/// way there from an input; the design checks refuse it at load.
pub fn curvature_from_derivatives(
    d1: [[f64; 3]; 2],
    d2: [[f64; 3]; 3],
    n_out: &Vector3<f64>,
) -> Curvature {
    let undefined = Curvature {
        k: [f64::NAN; 2],
        dir: [[f64::NAN; 3]; 2],
    };
    if d1.iter().chain(d2.iter()).flatten().any(|x| !x.is_finite()) {
        return undefined;
    }
    let ru = Vector3::from(d1[0]);
    let rv = Vector3::from(d1[1]);
    let mut n = ru.cross(&rv).normalize();
    if n.dot(n_out) < 0.0 {
        n = -n;
    }
    let first = Matrix2::new(ru.dot(&ru), ru.dot(&rv), ru.dot(&rv), rv.dot(&rv));
    let second = Matrix2::new(
        Vector3::from(d2[0]).dot(&n),
        Vector3::from(d2[1]).dot(&n),
        Vector3::from(d2[1]).dot(&n),
        Vector3::from(d2[2]).dot(&n),
    );
    // Symmetric form: I^{-1/2} II I^{-1/2} via Cholesky I = C Cᵀ.
    let Some(c) = first.cholesky().map(|c| c.l()) else {
        return undefined;
    };
    let Some(ci) = c.try_inverse() else {
        return undefined;
    };
    let m = ci * second * ci.transpose();
    let eig = m.symmetric_eigen();
    let mut out = Curvature {
        k: [0.0; 2],
        dir: [[0.0; 3]; 2],
    };
    let mut idx = [0usize, 1];
    idx.sort_by(|&a, &b| (-eig.eigenvalues[a]).total_cmp(&(-eig.eigenvalues[b])));
    for (o, &i) in idx.iter().enumerate() {
        out.k[o] = -eig.eigenvalues[i];
        let w = ci.transpose() * eig.eigenvectors.column(i);
        let t = (ru * w[0] + rv * w[1]).normalize();
        out.dir[o] = [t[0], t[1], t[2]];
    }
    out
}
