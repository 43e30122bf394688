//! A gear pair's flanks, ready for contact analysis: the four generated flanks
//! bounded by their blanks, the active region of each flank pair, and the
//! pinion's ease-off centred on its tooth's contact interval.

use crate::design::{Member, PairData};
use crate::ease_off::EaseOff;
use crate::error::GeometryError;
use crate::flank::{Bounds, Flank, FlankPoint};
use crate::generation::{Generator, MemberFrame, Side};
use serde::Serialize;

/// A pinion flank and its mating wheel flank on one side.
#[derive(Debug, Clone)]
pub struct FlankPair {
    pub side: Side,
    pub pinion: Flank,
    pub wheel: Flank,
    /// Wheel rotation (rad) added to −(z₁/z₂) φ₁ for conjugate contact of tooth j with wheel tooth −j.
    pub wheel_offset: f64,
    /// Pinion roll range of the active region of tooth 0, rad.
    pub roll_range: [f64; 2],
    /// The pinion's rigid pose relative to the wheel in the fixed frame
    /// (misalignments, [`crate::misalignment`]); `None` for the aligned pair,
    /// which the analyses treat exactly as before misalignments existed.
    pub pose: Option<crate::misalignment::Pose>,
}

/// Both sides of a pair.
#[derive(Debug, Clone)]
pub struct PairGeometry {
    pub data: PairData,
    pub generator: Generator,
    pub frames: [MemberFrame; 2],
    pub sides: [FlankPair; 2],
}

/// Sign of the pinion's rotation when it drives with `side` (the wheel turns the other way).
pub fn pinion_direction(data: &PairData, side: Side) -> f64 {
    let h = crate::generation::trace_sign(data.members[0].hand);
    match side {
        Side::Drive => -h,
        Side::Coast => h,
    }
}

/// Grid used to find the active region of a flank pair.
const REGION_GRID: usize = 41;

/// Tolerance (m) of the active-region test at grid nodes: the flank grids'
/// toe and heel rows lie exactly on the face-width bounds, and (L, d) comes
/// back from Newton to 1e-13 m, so without it round-off decides whether a
/// whole edge row counts as active.
pub const EDGE_TOL: f64 = 1e-11;

impl PairGeometry {
    pub fn new(data: &PairData) -> Result<Self, GeometryError> {
        Self::build(data, None)
    }

    /// Builds the pair; with a design-file path, first runs the tooth checks
    /// ([`PairGeometry::check_teeth`]) on the bare flanks.
    pub fn build(
        data: &PairData,
        checked: Option<&std::path::Path>,
    ) -> Result<Self, GeometryError> {
        let generator = Generator::new(data);
        let frames = [
            MemberFrame::new(data, Member::Pinion),
            MemberFrame::new(data, Member::Wheel),
        ];
        let k1 = frames[0].roll_ratio;
        let a2 = frames[1].axis();
        let bare = |side: Side| -> Result<FlankPair, GeometryError> {
            let flank = |m: Member| -> Result<Flank, GeometryError> {
                Ok(Flank::new(
                    *generator.flank(m, side),
                    Bounds::new(data, m, side),
                    None,
                    k1,
                    a2,
                ))
            };
            let (pinion, wheel) = (flank(Member::Pinion)?, flank(Member::Wheel)?);
            Ok(FlankPair {
                side,
                wheel_offset: -frames[1].roll_ratio * (wheel.gen.phase - pinion.gen.phase),
                pinion,
                wheel,
                roll_range: [0.0, 0.0],
                pose: None,
            })
        };
        let mut geom = PairGeometry {
            data: data.clone(),
            generator: generator.clone(),
            frames,
            sides: [bare(Side::Drive)?, bare(Side::Coast)?],
        };
        if let Some(path) = checked {
            geom.check_teeth(path)?;
        }
        for fp in geom.sides.iter_mut() {
            fp.pinion.fit_fillet_limit()?;
            fp.wheel.fit_fillet_limit()?;
            fp.roll_range = fp.active_roll_range()?;
            let vertex = 0.5 * (fp.roll_range[0] + fp.roll_range[1]);
            let settings = match &data.machine_settings {
                Some(ms) => Some(crate::machine::deviation::deviation(fp, ms)?.surface()?),
                None => None,
            };
            fp.pinion.ease = Some(
                EaseOff::new(&data.ease_off, vertex, data.mesh_cycle()).with_settings(settings),
            );
        }
        Ok(geom)
    }
}

impl PairGeometry {
    /// Places the bodies with `poses` (both sides of the pair): the pinion's
    /// pose relative to the wheel enters every gap; `None` aligns the pair.
    /// The flanks, their bounds and roll ranges are body-fixed and stay.
    pub fn set_poses(&mut self, poses: Option<crate::misalignment::BodyPoses>) {
        for fp in self.sides.iter_mut() {
            fp.pose = poses.map(|p| p.relative());
        }
    }

    /// Places the bodies with the misalignments `m` (aligned when all zero).
    pub fn misalign(&mut self, m: &crate::misalignment::Misalignment) {
        let poses = (!m.is_zero()).then(|| m.poses(&self.data));
        self.set_poses(poses);
    }

    pub fn side(&self, side: Side) -> &FlankPair {
        &self.sides[side.index()]
    }

    pub fn flank(&self, m: Member, side: Side) -> &Flank {
        let s = self.side(side);
        match m {
            Member::Pinion => &s.pinion,
            Member::Wheel => &s.wheel,
        }
    }
}

/// Whether a pinion point's conjugate mate lies on the wheel flank.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Activity {
    pub on_pinion: bool,
    pub on_wheel: bool,
}

impl FlankPair {
    /// Pinion point at generating parameters and whether it is in the active region.
    pub fn point(&self, u: f64, v: f64, tol: f64) -> (FlankPoint, bool) {
        let p = self.pinion.eval_uv(u, v);
        let (lw, dw) = self.wheel.ld(u, v);
        let ok =
            self.pinion.bounds.contains(p.l, p.d, tol) && self.wheel.bounds.contains(lw, dw, tol);
        (p, ok)
    }

    /// Is (u, v) in the active region (on both flanks)?
    pub fn is_active(&self, u: f64, v: f64, tol: f64) -> bool {
        let (l, d) = self.pinion.ld(u, v);
        let (lw, dw) = self.wheel.ld(u, v);
        self.pinion.bounds.contains(l, d, tol) && self.wheel.bounds.contains(lw, dw, tol)
    }

    /// Pinion roll range over the active region: along every grid row of the
    /// pinion flank the active interval's ends are found by bisection.
    fn active_roll_range(&self) -> Result<[f64; 2], GeometryError> {
        let n = REGION_GRID;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let grid = self.pinion_grid(n, n)?;
        let mut consider = |u: f64, v: f64| {
            let r = self.pinion.eval_uv(u, v).pinion_roll;
            lo = lo.min(r);
            hi = hi.max(r);
        };
        // Rows along the face (fixed η) and columns along the profile (fixed ξ).
        for dir in 0..2 {
            for a in 0..n {
                let node = |b: usize| {
                    if dir == 0 {
                        grid[b * n + a]
                    } else {
                        grid[a * n + b]
                    }
                };
                let act: Vec<bool> = (0..n)
                    .map(|b| {
                        let [u, v] = node(b);
                        self.is_active(u, v, EDGE_TOL)
                    })
                    .collect();
                for b in 0..n {
                    if !act[b] {
                        continue;
                    }
                    let [u, v] = node(b);
                    consider(u, v);
                    for nb in [b.wrapping_sub(1), b + 1] {
                        if nb < n && !act[nb] {
                            let [u, v] = bisect_boundary(self, node(b), node(nb));
                            consider(u, v);
                        }
                    }
                }
            }
        }
        Ok([lo, hi])
    }

    /// (u, v) of the pinion flank grid: index i·n_eta + k at (ξ_i, η_k), uniform in [0, 1]².
    pub fn pinion_grid(&self, n_xi: usize, n_eta: usize) -> Result<Vec<[f64; 2]>, GeometryError> {
        let mut out = Vec::with_capacity(n_xi * n_eta);
        let mut last: Option<[f64; 2]> = None;
        for i in 0..n_xi {
            let xi = i as f64 / (n_xi - 1) as f64;
            for k in 0..n_eta {
                let eta = k as f64 / (n_eta - 1) as f64;
                let (l, d) = self.pinion.bounds.from_unit(xi, eta);
                let uv = match last {
                    Some(s) => self
                        .pinion
                        .solve_ld_from(l, d, s)
                        .or_else(|_| self.pinion.solve_ld(l, d))?,
                    None => self.pinion.solve_ld(l, d)?,
                };
                last = Some(uv);
                out.push(uv);
            }
            last = Some(out[i * n_eta]);
        }
        Ok(out)
    }
}

/// Boundary of the active region between an active and an inactive (u, v).
fn bisect_boundary(fp: &FlankPair, inside: [f64; 2], outside: [f64; 2]) -> [f64; 2] {
    let (mut a, mut b) = (inside, outside);
    for _ in 0..40 {
        let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        if fp.is_active(m[0], m[1], EDGE_TOL) {
            a = m;
        } else {
            b = m;
        }
    }
    a
}

/// Top land of a member at cone distance `l`: arc between the tips of the
/// concave and convex flanks of tooth 0, positive while the tooth has a top land, m.
pub fn top_land(g: &PairGeometry, m: Member, l: f64) -> Result<f64, GeometryError> {
    let angle = |side: Side, d: f64| -> Result<(f64, f64), GeometryError> {
        let p = g.flank(m, side).at(l, d)?;
        Ok((p.pos[1].atan2(p.pos[0]), p.pos[0].hypot(p.pos[1])))
    };
    let b = g.flank(m, Side::Drive).bounds;
    let d_tip = b.face.at(l, b.rm);
    let (a0, _) = angle(Side::Drive, 0.0)?;
    let (c0, _) = angle(Side::Coast, 0.0)?;
    let (a1, rho) = angle(Side::Drive, d_tip)?;
    let (c1, _) = angle(Side::Coast, d_tip)?;
    let wrap = |x: f64| {
        (x + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
    };
    let s0 = wrap(c0 - a0).signum();
    Ok(rho * wrap(c1 - a1) * s0 * g.data.spiral_angle.cos())
}

/// Undercut test along the profile at cone distance `l`: the map from
/// generating parameters to (L, d) must keep its orientation from the pitch
/// cone down to the fillet limit; a fold means the generating tool cut away
/// flank it had generated (undercut). Returns the lowest regular height.
pub fn undercut_limit(f: &Flank, l: f64) -> Result<Option<f64>, GeometryError> {
    let d_low = f.bounds.low.at(l, f.bounds.rm);
    let n = 40;
    let mut start = f.solve_ld(l, 0.0)?;
    let det = |uv: [f64; 2]| {
        let h = 1e-7;
        let (l0, d0) = f.ld(uv[0], uv[1]);
        let (lu, du) = f.ld(uv[0] + h, uv[1]);
        let (lv, dv) = f.ld(uv[0], uv[1] + h);
        (lu - l0) * (dv - d0) - (lv - l0) * (du - d0)
    };
    let s0 = det(start).signum();
    for k in 1..=n {
        let d = d_low * k as f64 / n as f64;
        match f.solve_ld_from(l, d, start) {
            Ok(uv) if det(uv).signum() == s0 => start = uv,
            _ => return Ok(Some(d_low * (k - 1) as f64 / n as f64)),
        }
    }
    Ok(None)
}

impl PairGeometry {
    /// Loads a design file, builds the pair and runs the tooth checks
    /// (top land at toe, mean and heel; undercut), naming the file on failure.
    pub fn from_design_file(path: &std::path::Path) -> Result<Self, GeometryError> {
        let data = crate::design_file::load_pair(path)?;
        PairGeometry::build(&data, Some(path))
    }

    /// Smallest top land of both members at toe, mean and heel, m.
    fn smallest_top_land(&self) -> Result<f64, GeometryError> {
        let d = &self.data;
        let mut least = f64::INFINITY;
        for m in [Member::Pinion, Member::Wheel] {
            for l in [
                d.inner_cone_distance(),
                d.mean_cone_distance,
                d.outer_cone_distance(),
            ] {
                least = least.min(top_land(self, m, l)?);
            }
        }
        Ok(least)
    }

    /// When the teeth come to a point because the cutter radius is small
    /// (face milling with a constant slot width makes the tooth thin toward
    /// toe or heel the more, the smaller the cutter), the smallest cutter
    /// radius, up to the allowed 4 R_m, with a positive top land everywhere
    /// (bisection on rebuilt pairs). `None` when no cutter radius in
    /// [current, 4 R_m] helps: then the addendum or the tooth thickness is
    /// the cause.
    fn cutter_radius_for_top_land(&self) -> Result<Option<f64>, GeometryError> {
        let top_land_with = |r: f64| -> Option<f64> {
            let mut data = self.data.clone();
            data.cutter_radius = r;
            let g = PairGeometry::build(&data, None).ok()?;
            g.smallest_top_land().ok()
        };
        let mut lo = self.data.cutter_radius;
        let mut hi = 4.0 * self.data.mean_cone_distance;
        if hi <= lo || !top_land_with(hi).is_some_and(|t| t > 0.0) {
            return Ok(None);
        }
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if top_land_with(mid).is_some_and(|t| t > 0.0) {
                hi = mid;
            } else {
                lo = mid;
            }
            if hi - lo < 1e-5 {
                break;
            }
        }
        Ok(Some(hi))
    }

    /// Rejects pointed teeth and undercut flanks.
    pub fn check_teeth(&self, path: &std::path::Path) -> Result<(), GeometryError> {
        use crate::limits::design as design_limits;
        let d = &self.data;
        for m in [Member::Pinion, Member::Wheel] {
            for (where_, l) in [
                ("toe", d.inner_cone_distance()),
                ("mean", d.mean_cone_distance),
                ("heel", d.outer_cone_distance()),
            ] {
                let tl = top_land(self, m, l)?;
                if tl <= 0.0 {
                    if let Some(r_min) = self.cutter_radius_for_top_land()? {
                        let entry = &design_limits::POINTED_TEETH_CUTTER;
                        return Err(entry
                            .refuse(
                                path,
                                entry.field,
                                format!("{}", d.cutter_radius * 1e3),
                                format!(
                                "pointed teeth: the {} top land at the {where_} is {:.3} mm; with this cutter radius the tooth thins along the face toward the {where_}. The smallest cutter radius with a positive top land at toe, mean and heel is {:.1} mm",
                                m.name(),
                                tl * 1e3,
                                r_min * 1e3
                            ),
                            )
                            .into());
                    }
                    return Err(design_limits::POINTED_TEETH_ADDENDUM
                        .refuse(
                            path,
                            &format!("{}.mean_addendum_mm", m.name()),
                            format!("{}", d.member(m).mean_addendum * 1e3),
                            format!(
                                "pointed teeth: the top land at the {where_} is {:.3} mm, it must be > 0 (reduce the addendum or widen the tooth)",
                                tl * 1e3
                            ),
                        )
                        .into());
                }
                for side in [Side::Drive, Side::Coast] {
                    if let Some(lim) = undercut_limit(self.flank(m, side), l)? {
                        return Err(design_limits::UNDERCUT
                            .refuse(
                                path,
                                &format!("{}.mean_dedendum_mm", m.name()),
                                format!("{}", d.member(m).mean_dedendum * 1e3),
                                format!(
                                "undercut: the {} flank at the {where_} is generated regularly only down to {:.3} mm below the pitch cone, above the fillet limit {:.3} mm (more teeth, a larger pressure angle or profile shift, or a smaller dedendum)",
                                side.flank_name(m),
                                -lim * 1e3,
                                -self.flank(m, side).bounds.low.at(l, d.mean_cone_distance) * 1e3
                            ),
                        )
                        .into());
                    }
                }
            }
        }
        Ok(())
    }
}

/// Tooth pairs j (pinion tooth j with wheel tooth −j) whose roll φ + jτ lies
/// inside the active roll range [r₀, r₁] at pinion angle φ.
pub fn pairs_in_contact(phi: f64, roll_range: [f64; 2], tau: f64) -> Vec<i32> {
    let jmin = ((roll_range[0] - phi) / tau).ceil() as i32;
    let jmax = ((roll_range[1] - phi) / tau).floor() as i32;
    (jmin..=jmax).collect()
}

/// Pinion and wheel teeth (indices mod z) that come into contact on `side`
/// while the pinion turns `mesh_cycles` mesh cycles from the entry of tooth 0.
pub fn teeth_in_contact(
    g: &PairGeometry,
    side: Side,
    mesh_cycles: f64,
    step: f64,
) -> (Vec<usize>, Vec<usize>) {
    let n = (mesh_cycles * g.data.mesh_cycle() / step).round() as i64;
    teeth_over_sweep(g, side, side, 0..=n, step, 0)
}

/// [`teeth_in_contact`] at the sweep positions k in `ks` (k < 0: before
/// the sweep's start, as the multibody table's lead-in).
pub fn teeth_in_contact_at(
    g: &PairGeometry,
    side: Side,
    ks: std::ops::RangeInclusive<i64>,
    step: f64,
) -> (Vec<usize>, Vec<usize>) {
    teeth_over_sweep(g, side, side, ks, step, 0)
}

/// Pinion and wheel teeth (indices mod z) whose `contact` flank touches at
/// the pinion angles φ_k = r₀ + d k `step` of the `sweep` side's sweep (r₀
/// its roll range's start, d its pinion direction), k in `ks`; the wheel's
/// model tooth −j is the body's tooth −j + `wheel_shift`.
fn teeth_over_sweep(
    g: &PairGeometry,
    sweep: Side,
    contact: Side,
    ks: std::ops::RangeInclusive<i64>,
    step: f64,
    wheel_shift: i64,
) -> (Vec<usize>, Vec<usize>) {
    let start = g.side(sweep).roll_range[0];
    let range = g.side(contact).roll_range;
    let tau = g.data.mesh_cycle();
    let dir = pinion_direction(&g.data, sweep);
    let (z1, z2) = (
        g.data.members[0].teeth as i64,
        g.data.members[1].teeth as i64,
    );
    let mut p = std::collections::BTreeSet::new();
    let mut w = std::collections::BTreeSet::new();
    for k in ks {
        for j in pairs_in_contact(start + dir * step * k as f64, range, tau) {
            let j = j as i64;
            p.insert(j.rem_euclid(z1) as usize);
            w.insert((-j + wheel_shift).rem_euclid(z2) as usize);
        }
    }
    (p.into_iter().collect(), w.into_iter().collect())
}

/// How the opposite flank pair's wheel teeth map onto the loaded pair's.
///
/// Both pairs turn the pinion through the same angle φ, but each places the
/// wheel at its own conjugate offset: ψ = −(z₁/z₂) φ + o (+ its lag). The
/// offsets differ by the conjugate flanks' angular backlash B plus whole
/// wheel pitches, d (o_l − o_o) = B + m τ₂ with d the loaded side's pinion
/// direction and B reduced to the nearest pitch (the flanks across one tooth
/// space). Placed with the backlash B, the opposite model's wheel stands m
/// pitches off the physical wheel: its tooth k is the body's tooth k − d m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OppositePlacement {
    /// Angular backlash B of the conjugate flanks at the wheel, rad.
    pub backlash: f64,
    /// Physical wheel tooth of the opposite model's wheel tooth k: k + shift.
    pub wheel_tooth_shift: i64,
}

impl OppositePlacement {
    /// The `opposite` flank pair's placement against the `loaded` one's,
    /// `direction` being the loaded side's pinion direction.
    pub fn new(loaded: &FlankPair, opposite: &FlankPair, direction: f64) -> Self {
        let pitch2 = opposite.wheel.gen.frame.pitch();
        let b = direction * (loaded.wheel_offset - opposite.wheel_offset);
        let m = (b / pitch2).round();
        OppositePlacement {
            backlash: b - pitch2 * m,
            wheel_tooth_shift: -(direction * m) as i64,
        }
    }
}

impl PairGeometry {
    /// The opposite side's placement against the `loaded` side's.
    pub fn opposite_placement(&self, loaded: Side) -> OppositePlacement {
        OppositePlacement::new(
            self.side(loaded),
            self.side(loaded.other()),
            pinion_direction(&self.data, loaded),
        )
    }
}

/// Pinion and wheel teeth (physical indices mod z) whose flank opposite to
/// `loaded` can touch while the pinion turns `mesh_cycles` mesh cycles of the
/// loaded side's sweep (from the entry of its tooth 0), with one mesh cycle
/// of margin at either end for the tables that span the sweep.
pub fn opposite_teeth_in_contact(
    g: &PairGeometry,
    loaded: Side,
    mesh_cycles: f64,
    step: f64,
) -> (Vec<usize>, Vec<usize>) {
    let tau = g.data.mesh_cycle();
    let margin = (tau / step).ceil() as i64;
    let n = (mesh_cycles * tau / step).round() as i64;
    // Both sides share the pinion angle φ.
    teeth_over_sweep(
        g,
        loaded,
        loaded.other(),
        -margin..=n + margin,
        step,
        g.opposite_placement(loaded).wheel_tooth_shift,
    )
}
