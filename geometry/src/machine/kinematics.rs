//! The generating motion of a face-milling machine and the flank it cuts.
//!
//! Machine frame ([`crate::machine`]): origin at the machine centre, z the
//! cradle axis. The cutter centre sits on the cradle at the radial setting
//! S_r and cradle angle q, C = S_r (cos q, sin q, 0); its axis is the cradle
//! axis tilted by the tilt i toward the direction q + j in the cradle plane
//! (j the swivel), c = cos i e_z + sin i (cos(q + j), sin(q + j), 0), by the
//! rotation T about e_z × that direction. A straight blade of radius r_b in
//! the reference plane and blade angle α sweeps the cone
//!
//!   X(ζ, θ) = C + T [ρ(ζ) cos θ, ρ(ζ) sin θ, ζ],   ρ = r_b + σ ζ tan α,
//!   N(ζ, θ) = T [cos α cos θ, cos α sin θ, −σ sin α],
//!
//! σ = +1 on the drive side (the blade cone widening toward +z) and −1 on
//! the coast side, N pointing away from the cutter axis. A curved blade
//! (profile curvature κ) bends away from the straight one by κ s²/2 along
//! its normal, s = ζ / cos α the length along the straight blade, toward
//! the work's material (its ends cut deeper: profile crowning for κ > 0);
//! its normal turns by κ s. ζ then labels the blade point by the straight
//! blade's height.
//!
//! The cradle turns by φ_c about z; the work, whose axis a makes the
//! machine root angle γ_m with the cradle plane (pinion below, wheel above,
//! in the x–z plane) and whose apex sits at
//! A = (0, E_m, ΔX_B) + ΔX_D a (blank offset, sliding base, machine centre
//! to back), turns about a by
//!
//!   φ_w(φ_c) = k (φ_c − C φ_c² − D φ_c³),   k = ∓R_a (pinion −, wheel +),
//!
//! R_a the ratio of roll and 2C, 6D the modified-roll coefficients. The
//! tool point X_f = R_z(φ_c) X touches the work where the relative velocity
//! is tangent (equation of meshing):
//!
//!   f(φ_c) = N_f · (e_z × X_f) − φ_w′(φ_c) N_f · (a × (X_f − A)) = 0,
//!
//! solved for φ_c by Newton (bracketed where Newton strays). The work's
//! point is X_m = R_z(δ − φ_w) Mᵀ (X_f − A), M the work's axes and δ a
//! rotation of the cut flank about the work axis ([`Machine::indexed`],
//! 0 unless set). A Formate
//! flank (not generated) is the cutter's imprint with cradle and work at
//! rest: φ_c = φ_w = 0, every cone point.
//!
//! With γ_m = γ (pitch angle), R_a = 1 / sin γ and no offsets, modified
//! roll or tilt the cradle is the complementary crown gear of
//! [`crate::generation`] and the relative motion a rotation about the
//! pitch line, which gives its closed-form roll.

use crate::design::Member;
use crate::generation::{outward, MemberFrame, Side};
use crate::machine::settings::FlankSettings;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};

/// Largest |φ_c| (rad) the bracket search of the equation of meshing scans.
const MAX_ROLL: f64 = 1.5;
/// Step of that scan, rad.
const SCAN_STEP: f64 = 0.01;

/// One flank's machine, ready to generate.
#[derive(Debug, Clone, Copy)]
pub struct Machine {
    pub settings: FlankSettings,
    member: Member,
    side: Side,
    /// σ: +1 drive side, −1 coast side.
    slope: f64,
    /// +1 when the work's outward normal is N, else −1.
    outward: f64,
    /// Signed ratio of roll k.
    k: f64,
    /// Work axes (columns) in the machine frame.
    axes: Matrix3<f64>,
    apex: Vector3<f64>,
    centre: Vector3<f64>,
    tilt: Matrix3<f64>,
    sin_a: f64,
    cos_a: f64,
    /// A rotation of the cut flank about the work axis, rad (the tooth's
    /// angular position, [`Machine::indexed`]).
    index: f64,
}

/// A generated point in the work frame.
#[derive(Debug, Clone, Copy)]
pub struct CutPoint {
    pub pos: Vector3<f64>,
    /// Outward unit normal.
    pub normal: Vector3<f64>,
    /// Cradle angle at which it is cut, rad.
    pub cradle_roll: f64,
}

impl Machine {
    pub fn new(settings: &FlankSettings, m: Member, side: Side) -> Self {
        let s = *settings;
        let axes = MemberFrame::axes_at(m, s.machine_root_angle);
        let a = axes.column(2).into_owned();
        let apex = Vector3::new(0.0, s.blank_offset, s.sliding_base) + s.machine_center_to_back * a;
        let (sq, cq) = s.cradle_angle.sin_cos();
        let centre = Vector3::new(cq, sq, 0.0) * s.radial_setting;
        let dir = s.cradle_angle + s.cutter_swivel;
        let about = Unit::new_normalize(Vector3::new(-dir.sin(), dir.cos(), 0.0));
        let tilt = Rotation3::from_axis_angle(&about, s.cutter_tilt).into_inner();
        Machine {
            settings: s,
            member: m,
            side,
            slope: match side {
                Side::Drive => 1.0,
                Side::Coast => -1.0,
            },
            outward: outward(m, side),
            k: MemberFrame::roll_sign(m) * s.ratio_of_roll,
            axes,
            apex,
            centre,
            tilt,
            sin_a: s.blade_angle.sin(),
            cos_a: s.blade_angle.cos(),
            index: 0.0,
        }
    }

    /// The same machine with the cut flank turned by `index` (rad) about
    /// the work axis: a rigid rotation of the work, which leaves the
    /// equation of meshing as it is.
    pub fn indexed(mut self, index: f64) -> Self {
        self.index = index;
        self
    }

    /// The member this machine cuts.
    pub fn member(&self) -> Member {
        self.member
    }

    /// The side of the flank it cuts.
    pub fn side(&self) -> Side {
        self.side
    }

    /// The rotation of [`Machine::indexed`], rad.
    pub fn index(&self) -> f64 {
        self.index
    }

    /// Cone point X and normal N (away from the cutter axis) at height ζ
    /// along the cutter axis and angle θ about it, cradle at rest.
    pub fn tool(&self, zeta: f64, theta: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (st, ct) = theta.sin_cos();
        // In the blade's radial plane (radius, axial): the straight blade
        // along t, its normal n_b, s the length along it; a curved blade
        // bends away by κ s²/2 (material removed toward its ends).
        let t = [self.slope * self.sin_a, self.cos_a];
        let nb = [self.cos_a, -self.slope * self.sin_a];
        let s = zeta / self.cos_a;
        let bend = -self.outward * 0.5 * self.settings.blade_profile_curvature * s * s;
        let rho = self.settings.blade_radius + s * t[0] + bend * nb[0];
        let z = zeta + bend * nb[1];
        let tilt = self.outward * self.settings.blade_profile_curvature * s;
        let (nr, nz) = (nb[0] + tilt * t[0], nb[1] + tilt * t[1]);
        let norm = nr.hypot(nz);
        let p = self.centre + self.tilt * Vector3::new(rho * ct, rho * st, z);
        let n = self.tilt * Vector3::new(nr * ct / norm, nr * st / norm, nz / norm);
        (p, n)
    }

    /// The cone parameters (ζ, θ) of the point of the cone nearest `x`
    /// along the cutter's radial plane (x in the machine frame, cradle at
    /// rest): ζ along the cutter axis, θ about it.
    pub fn tool_parameters(&self, x: &Vector3<f64>) -> (f64, f64) {
        let local = self.tilt.transpose() * (x - self.centre);
        (local.z, local.y.atan2(local.x))
    }

    /// Work rotation at cradle angle φ_c and its derivative dφ_w/dφ_c.
    pub fn work_roll(&self, phic: f64) -> (f64, f64) {
        let s = &self.settings;
        let (c, d) = (0.5 * s.modified_roll_2c, s.modified_roll_6d / 6.0);
        (
            self.k * phic * (1.0 - phic * (c + d * phic)),
            self.k * (1.0 - phic * (2.0 * c + 3.0 * d * phic)),
        )
    }

    /// The equation of meshing's residual f(φ_c) for the cone point `x`
    /// with normal `n` (cradle at rest), m.
    pub fn meshing(&self, x: &Vector3<f64>, n: &Vector3<f64>, phic: f64) -> f64 {
        let r = self.cradle(phic);
        let (xf, nf) = (r * x, r * n);
        let a = self.axes.column(2);
        let (_, rate) = self.work_roll(phic);
        nf.dot(&Vector3::z().cross(&xf)) - rate * nf.dot(&a.cross(&(xf - self.apex)))
    }

    /// The cradle angle at which the cone point (`x`, `n`) is cut, Newton
    /// from `guess`; where Newton strays, the sign change of f nearest the
    /// guess (scanned up to ±1.5 rad) refined by bisection. None where f
    /// has no root there.
    pub fn cradle_roll(&self, x: &Vector3<f64>, n: &Vector3<f64>, guess: f64) -> Option<f64> {
        let f = |p: f64| self.meshing(x, n, p);
        let scale = x.norm().max(1e-3);
        let tol = 1e-13 * scale;
        let mut p = guess;
        for _ in 0..20 {
            let h = 1e-6;
            let d = (f(p + h) - f(p - h)) / (2.0 * h);
            if d.abs() < 1e-6 * scale {
                break;
            }
            let step = f(p) / d;
            p -= step;
            if !p.is_finite() || (p - guess).abs() > MAX_ROLL {
                break;
            }
            if step.abs() < 1e-14 && f(p).abs() <= tol {
                return Some(p);
            }
        }
        self.bracketed_root(&f, guess, tol)
    }

    /// The root of `f` whose bracket lies nearest `guess`, by bisection.
    fn bracketed_root(&self, f: &dyn Fn(f64) -> f64, guess: f64, tol: f64) -> Option<f64> {
        let f0 = f(guess);
        if f0.abs() <= tol {
            return Some(guess);
        }
        let steps = (MAX_ROLL / SCAN_STEP) as usize;
        for i in 0..steps {
            for dir in [1.0, -1.0] {
                let (a, b) = (
                    guess + dir * SCAN_STEP * i as f64,
                    guess + dir * SCAN_STEP * (i + 1) as f64,
                );
                let (mut lo, mut hi) = (a.min(b), a.max(b));
                let (mut flo, fhi) = (f(lo), f(hi));
                if flo * fhi > 0.0 {
                    continue;
                }
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    let fm = f(mid);
                    if (fm < 0.0) == (flo < 0.0) {
                        lo = mid;
                        flo = fm;
                    } else {
                        hi = mid;
                    }
                    if hi - lo < 1e-15 {
                        break;
                    }
                }
                return Some(0.5 * (lo + hi));
            }
        }
        None
    }

    /// The work-frame point of the machine-frame point `x` (cradle at
    /// rest) carried to cradle angle φ_c.
    pub fn to_work(&self, x: &Vector3<f64>, phic: f64) -> Vector3<f64> {
        self.work_rotation(phic) * (self.axes.transpose() * (self.cradle(phic) * x - self.apex))
    }

    /// A direction `v` of the machine frame, carried like [`Machine::to_work`].
    fn direction_to_work(&self, v: &Vector3<f64>, phic: f64) -> Vector3<f64> {
        self.work_rotation(phic) * (self.axes.transpose() * (self.cradle(phic) * v))
    }

    /// The cradle's rotation R_z(φ_c).
    fn cradle(&self, phic: f64) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vector3::z_axis(), phic)
    }

    /// From the machine frame's work axes into the turning work:
    /// R_z(index − φ_w(φ_c)).
    fn work_rotation(&self, phic: f64) -> Rotation3<f64> {
        let (phiw, _) = self.work_roll(phic);
        Rotation3::from_axis_angle(&Vector3::z_axis(), self.index - phiw)
    }

    /// The flank point cut by the cone point (ζ, θ): generated, at the
    /// cradle angle of the equation of meshing (Newton from `guess`);
    /// Formate, the cone point itself with cradle and work at rest.
    pub fn cut(&self, zeta: f64, theta: f64, guess: f64) -> Option<CutPoint> {
        let (x, n) = self.tool(zeta, theta);
        let phic = if self.settings.generated {
            self.cradle_roll(&x, &n, guess)?
        } else {
            0.0
        };
        Some(CutPoint {
            pos: self.to_work(&x, phic),
            normal: self.direction_to_work(&n, phic) * self.outward,
            cradle_roll: phic,
        })
    }
}
