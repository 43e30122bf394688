//! Both flank pairs in one force element: the coast side's table placed in
//! the drive side's coordinates across the backlash.
//!
//! Each side's [`MeshTable`] has its own coordinates: the pinion angle
//! φ = s + d q₁ (s the side's sweep start, d its pinion direction) and the
//! wheel angle ψ = −r s + o − d q₂ (o the side's conjugate wheel offset,
//! r = z₁/z₂), so that θ = r q₁ − q₂ is that side's wheel lag. The coast
//! side turns the other way (d_c = −d_d), and its coordinates are affine in
//! the drive side's:
//!
//!   q₁ᶜ = a − q₁,  a = d_d (s_c − s_d),
//!   q₂ᶜ = c − q₂,  c = r a + B,
//!   θᶜ = −B − θ,   B = d_d (o_d − o_c)  (mod the wheel pitch 2π/z₂),
//!
//! B being the conjugate flanks' angular backlash at the wheel: the drive
//! flanks touch at θ = θ₀(q₁), the coast flanks at θ = −B − θ₀ᶜ(q₁ᶜ), and the
//! free play between them is B + θ₀ + θ₀ᶜ. The coast potential
//! Vᶜ(a − q₁, c − q₂) adds to the drive side's: its gradient changes sign,
//! its Hessian does not. Reducing B to the nearest pitch renumbers the
//! wheel's teeth: the coast model's wheel tooth k is the body's tooth
//! k + shift ([`OppositePlacement`]), which the coast side's wheel
//! compliance applies, so that a blank that is not axisymmetric gives each
//! coast flank its own tooth's stiffness. Both tables are periodic
//! (axisymmetric blanks) or neither: a non-periodic coast table is built
//! over the drive table's range mirrored, q₁ᶜ = a − q₁ (see
//! [`Coast::mirrored_start`]).

use crate::multibody::mesh_table::{MeshState, MeshTable};
use crate::SolverError;
use geometry::pair::{FlankPair, OppositePlacement};

/// Angular backlash B = d_d (o_d − o_c) of the conjugate flanks at the
/// wheel, reduced to the nearest wheel pitch, rad: how far the wheel turns
/// against the drive direction from drive-flank to coast-flank contact.
pub fn conjugate_backlash(drive_fp: &FlankPair, coast_fp: &FlankPair, drive_direction: f64) -> f64 {
    OppositePlacement::new(drive_fp, coast_fp, drive_direction).backlash
}

/// The coast flanks' table in the drive side's coordinates.
#[derive(Debug, Clone)]
pub struct Coast {
    pub table: MeshTable,
    /// q₁ᶜ = a − q₁ and q₂ᶜ = c − q₂, rad.
    pub a: f64,
    pub c: f64,
    /// Angular backlash B of the conjugate flanks at the wheel, rad.
    pub backlash: f64,
}

impl Coast {
    /// Places the coast table `coast` (built on `coast_fp`) against the drive
    /// table `drive` (built on `drive_fp`).
    pub fn place(
        drive_fp: &FlankPair,
        drive: &MeshTable,
        coast_fp: &FlankPair,
        coast: MeshTable,
    ) -> Result<Self, SolverError> {
        let (sd, dd) = (drive.spec.start, drive.spec.direction);
        let (sc, dc) = (coast.spec.start, coast.spec.direction);
        if dd * dc >= 0.0 {
            return Err(SolverError::Table(format!(
                "coast table turns the pinion the same way as the drive table ({dc} vs {dd})"
            )));
        }
        if drive.spec.periodic != coast.spec.periodic {
            return Err(SolverError::Table(format!(
                "drive table periodic: {}, coast table periodic: {} (both or neither)",
                drive.spec.periodic, coast.spec.periodic
            )));
        }
        let r = drive.ratio;
        let backlash = conjugate_backlash(drive_fp, coast_fp, dd);
        let a = dd * (sc - sd);
        Ok(Coast {
            a,
            c: r * a + backlash,
            table: coast,
            backlash,
        })
    }

    /// Start (pinion angle, rad) of a non-periodic coast table that covers
    /// the non-periodic `drive` table's range mirrored: with the same step
    /// and number of positions it gives a = (positions − 1) · step, so that
    /// q₁ᶜ = a − q₁ runs over the coast table's range as q₁ runs over the
    /// drive table's.
    pub fn mirrored_start(drive: &MeshTable) -> f64 {
        let s = &drive.spec;
        s.start + s.direction * s.step * (s.positions - 1) as f64
    }

    /// Coast coordinates of the drive coordinates q.
    pub fn coordinates(&self, q: [f64; 2]) -> [f64; 2] {
        [self.a - q[0], self.c - q[1]]
    }

    /// The coast flanks' state at drive coordinates q: `theta` and `u` are
    /// the coast side's (its lag and its distance into contact), potential,
    /// gradient and Hessian are with respect to the drive coordinates.
    pub fn state(&self, q: [f64; 2]) -> Result<MeshState, SolverError> {
        let [q1, q2] = self.coordinates(q);
        let ms = self.table.state(q1, q2)?;
        Ok(MeshState {
            grad: [-ms.grad[0], -ms.grad[1]],
            ..ms
        })
    }

    /// Friction moments per unit friction coefficient (Φ₁, Φ₂) of the coast
    /// flanks and their derivatives with respect to the drive coordinates.
    /// With the pinion speed's sign flipped by the mapping, they enter the
    /// equations of motion exactly as the drive side's do.
    pub fn friction_state(&self, q: [f64; 2]) -> Result<([f64; 2], [[f64; 2]; 2]), SolverError> {
        let [q1, q2] = self.coordinates(q);
        let (phi, d) = self.table.friction_state(q1, q2)?;
        Ok((phi, d.map(|row| row.map(|x| -x))))
    }

    /// Drive lags at which the flanks touch at drive pinion rotation q₁:
    /// [θ₀(q₁) (drive flanks), −B − θ₀ᶜ(q₁ᶜ) (coast flanks)], rad.
    pub fn contact_lags(&self, drive: &MeshTable, q1: f64) -> Result<[f64; 2], SolverError> {
        Ok([
            drive.unloaded(q1)?[0],
            -self.backlash - self.table.unloaded(self.a - q1)?[0],
        ])
    }

    /// Free play between the flanks at drive pinion rotation q₁:
    /// B + θ₀(q₁) + θ₀ᶜ(q₁ᶜ), rad.
    pub fn free_play(&self, drive: &MeshTable, q1: f64) -> Result<f64, SolverError> {
        let [hi, lo] = self.contact_lags(drive, q1)?;
        Ok(hi - lo)
    }
}
