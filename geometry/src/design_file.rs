//! Reading a design file ([`load_pair`], [`DesignFile::load`],
//! [`DesignFile::to_pair`]) and its checks: every number finite and in range
//! (with the limit in the message), the data consistent with each other
//! (pitch angles from the tooth numbers before the cone angles that depend
//! on them), and the derived pair sound (cutter radius, tooth thickness,
//! spiral angle along the face). Each limit is an entry of
//! [`crate::limits::design`], which the checks test values against and
//! refuse with.

use crate::design::*;
use crate::error::InputError;
use crate::limits::design as lim;
use std::path::Path;

impl DesignFile {
    /// Reads and parses a design file (no semantic checks yet).
    pub fn load(path: &Path) -> Result<Self, InputError> {
        let text = InputError::read_text(path)?;
        Self::parse(&text, path)
    }

    /// Parses TOML text; `path` is used in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        toml::from_str(text).map_err(|e| InputError::parse(path, text, &e))
    }

    /// Checks the design and converts it to SI.
    pub fn to_pair(&self, path: &Path) -> Result<PairData, InputError> {
        check_design(self, path)?;
        let deg = f64::to_radians;
        let mm = |x: f64| x * 1e-3;
        let member = |d: &MemberDesign| MemberData {
            teeth: d.teeth,
            hand: d.hand,
            pitch_angle: deg(d.pitch_angle_deg),
            root_angle: deg(d.root_angle_deg),
            face_angle: deg(d.face_angle_deg),
            mean_addendum: mm(d.mean_addendum_mm),
            mean_dedendum: mm(d.mean_dedendum_mm),
            point_width: mm(d.point_width_mm),
            youngs_modulus: d.material.youngs_modulus_gpa * 1e9,
            poisson_ratio: d.material.poisson_ratio,
            density: d.material.density_kg_m3,
        };
        let p = &self.pair;
        // Exact pitch angles from the tooth numbers (the file's rounded values
        // were checked to 0.01°): the roll ratios must match z₁/z₂ exactly.
        let sigma = deg(p.shaft_angle_deg);
        let g1 = pinion_pitch_angle(self.pinion.teeth as f64, self.wheel.teeth as f64, sigma);
        let mut members = [member(&self.pinion), member(&self.wheel)];
        members[0].pitch_angle = g1;
        members[1].pitch_angle = sigma - g1;
        let pair = PairData {
            name: self.name.clone(),
            shaft_angle: deg(p.shaft_angle_deg),
            spiral_angle: deg(p.mean_spiral_angle_deg),
            normal_module: mm(p.mean_normal_module_mm),
            mean_cone_distance: mm(p.mean_cone_distance_mm),
            face_width: mm(p.face_width_mm),
            pressure_angle: [
                deg(p.drive_pressure_angle_deg),
                deg(p.coast_pressure_angle_deg),
            ],
            members,
            cutter_radius: mm(self.cutter.radius_mm),
            edge_radius: mm(self.cutter.edge_radius_mm),
            ease_off: self.ease_off.clone(),
            machine_settings: self
                .machine_settings
                .as_ref()
                .map(crate::machine::settings::MachineSettings::from_design),
            published: {
                let dir = path.parent().unwrap_or(Path::new("."));
                PublishedDesign {
                    loaded_te: self.published.loaded_te.as_ref().map(|f| dir.join(f)),
                    cpu: self.published.cpu.as_ref().map(|f| dir.join(f)),
                }
            },
        };
        check_derived(&pair, path)?;
        Ok(pair)
    }
}

/// Loads and checks a design file.
pub fn load_pair(path: &Path) -> Result<PairData, InputError> {
    DesignFile::load(path)?.to_pair(path)
}

/// Largest mean cone distance, mm (a 10 m pitch diameter).
pub const MAX_CONE_DISTANCE_MM: f64 = 5000.0;
/// Largest tooth number of either member.
pub const MAX_TEETH: u32 = 500;
/// Largest mean addendum or dedendum as a multiple of the mean normal module
/// (usual: about 1 and 1.25; strongly shifted pinions reach 2).
pub const MAX_DEPTH_MODULES: f64 = 3.0;
/// Cutter radius bounds as multiples of the mean cone distance. Usual
/// face-mill cutters lie between 0.5 and 1.5 R_m. Far above (from about
/// 1e4 R_m on the white-paper pair) the tooth trace is numerically straight
/// and the flank points are not found; below about 0.37 R_m the heel of the
/// 9-tooth seed pinions' convex flank is not reached by the generated surface
/// (both surfaced as "Newton did not converge").
pub const MIN_CUTTER_RADIUS_CONE_DISTANCES: f64 = 0.4;
pub const MAX_CUTTER_RADIUS_CONE_DISTANCES: f64 = 4.0;
/// Largest radial setting, in mean cone distances (cone distance plus the
/// largest cutter radius).
pub const MAX_RADIAL_SETTING_CONE_DISTANCES: f64 = 5.0;
/// Largest machine offset either way (sliding base, machine centre to
/// back, blank offset), in mean cone distances.
pub const MAX_OFFSET_CONE_DISTANCES: f64 = 0.5;
/// Largest magnitude of a topography deviation, µm.
pub const MAX_TOPOGRAPHY_UM: f64 = 1000.0;
/// Largest number of topography nodes along either direction.
pub const MAX_TOPOGRAPHY_NODES: usize = 200;

/// Checks that a name used as a file or directory name is a plain name: not
/// empty, at most 100 characters, no path separator, no `..`, no control
/// character, not `.`.
pub fn check_plain_name(path: &Path, field: &str, name: &str) -> Result<(), InputError> {
    let bad = if name.is_empty() {
        Some("must not be empty (it becomes a directory name)")
    } else if name.chars().count() > 100 {
        Some("must be at most 100 characters (it becomes a directory name)")
    } else if name.contains('/') || name.contains('\\') {
        Some("must be a plain name without '/' or '\\' (it becomes a directory name)")
    } else if name == "." || name.contains("..") {
        Some("must be a plain name without '..' and not '.' (it becomes a directory name)")
    } else if name.chars().any(char::is_control) {
        Some("must not contain control characters (it becomes a directory name)")
    } else {
        None
    };
    match bad {
        Some(limit) => Err(InputError::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            value: format!("{name:?}"),
            limit: limit.into(),
        }),
        None => Ok(()),
    }
}

fn check_design(d: &DesignFile, path: &Path) -> Result<(), InputError> {
    check_plain_name(path, lim::NAME.field, &d.name)?;
    check_pair(path, &d.pair)?;
    check_teeth_and_hands(path, d)?;
    let g1 = check_pitch_angles(path, d)?;
    check_members(path, d)?;
    check_module_and_clearance(path, d, g1)?;
    check_cutter_and_ease_off(path, d)?;
    check_machine_settings(path, d)
}

/// Every number of `[machine_settings]`, if given (the deviation of the
/// flanks they cut is checked when the flanks are built).
fn check_machine_settings(path: &Path, d: &DesignFile) -> Result<(), InputError> {
    let Some(ms) = &d.machine_settings else {
        return Ok(());
    };
    let rm = d.pair.mean_cone_distance_mm;
    for (member, m) in [("pinion", &ms.pinion), ("wheel", &ms.wheel)] {
        for (flank, f) in [("concave", &m.concave), ("convex", &m.convex)] {
            let at = |name: &str| format!("machine_settings.{member}.{flank}.{name}");
            for (l, name, v) in [
                (
                    &lim::SETTINGS_BLADE_ANGLE,
                    "blade_angle_deg",
                    f.blade_angle_deg,
                ),
                (
                    &lim::SETTINGS_BLADE_CURVATURE,
                    "blade_profile_curvature_per_m",
                    f.blade_profile_curvature_per_m,
                ),
                (
                    &lim::SETTINGS_CRADLE_ANGLE,
                    "cradle_angle_deg",
                    f.cradle_angle_deg,
                ),
                (
                    &lim::SETTINGS_ROOT_ANGLE,
                    "machine_root_angle_deg",
                    f.machine_root_angle_deg,
                ),
                (
                    &lim::SETTINGS_RATIO_OF_ROLL,
                    "ratio_of_roll",
                    f.ratio_of_roll,
                ),
                (
                    &lim::SETTINGS_ROLL_2C,
                    "modified_roll_2c",
                    f.modified_roll_2c,
                ),
                (
                    &lim::SETTINGS_ROLL_6D,
                    "modified_roll_6d",
                    f.modified_roll_6d,
                ),
                (&lim::SETTINGS_TILT, "cutter_tilt_deg", f.cutter_tilt_deg),
                (
                    &lim::SETTINGS_SWIVEL,
                    "cutter_swivel_deg",
                    f.cutter_swivel_deg,
                ),
            ] {
                l.check_at(path, &at(name), v)?;
            }
            for (l, name, v, scale) in [
                (
                    &lim::SETTINGS_BLADE_RADIUS,
                    "blade_radius_mm",
                    f.blade_radius_mm,
                    MAX_CUTTER_RADIUS_CONE_DISTANCES,
                ),
                (
                    &lim::SETTINGS_RADIAL,
                    "radial_setting_mm",
                    f.radial_setting_mm,
                    MAX_RADIAL_SETTING_CONE_DISTANCES,
                ),
            ] {
                let hi = scale * rm;
                l.check_with(path, &at(name), v, &[hi], || {
                    format!("must lie in (0, {hi}] ({scale} × pair.mean_cone_distance_mm)")
                })?;
            }
            let hi = MAX_OFFSET_CONE_DISTANCES * rm;
            for (l, name, v) in [
                (
                    &lim::SETTINGS_SLIDING_BASE,
                    "sliding_base_mm",
                    f.sliding_base_mm,
                ),
                (
                    &lim::SETTINGS_CENTRE_TO_BACK,
                    "machine_center_to_back_mm",
                    f.machine_center_to_back_mm,
                ),
                (
                    &lim::SETTINGS_BLANK_OFFSET,
                    "blank_offset_mm",
                    f.blank_offset_mm,
                ),
            ] {
                l.check_with(path, &at(name), v, &[-hi, hi], || {
                    format!("must lie in [-{hi}, {hi}] (± {MAX_OFFSET_CONE_DISTANCES} × pair.mean_cone_distance_mm)")
                })?;
            }
        }
    }
    Ok(())
}

/// The `[pair]` table: angles, module, cone distance and face width.
fn check_pair(path: &Path, p: &PairDesign) -> Result<(), InputError> {
    lim::SHAFT_ANGLE.check(path, p.shaft_angle_deg)?;
    lim::SPIRAL_ANGLE.check(path, p.mean_spiral_angle_deg)?;
    lim::NORMAL_MODULE.check(path, p.mean_normal_module_mm)?;
    lim::CONE_DISTANCE.check(path, p.mean_cone_distance_mm)?;
    lim::FACE_WIDTH.check(path, p.face_width_mm)?;
    lim::DRIVE_PRESSURE_ANGLE.check(path, p.drive_pressure_angle_deg)?;
    lim::COAST_PRESSURE_ANGLE.check(path, p.coast_pressure_angle_deg)?;
    // Usual limit: face width at most a third of the outer cone distance,
    // b <= (R_m + b/2) / 3, which is b <= 0.4 R_m (the entry's end).
    let re = p.mean_cone_distance_mm + 0.5 * p.face_width_mm;
    let l = &lim::FACE_WIDTH_OF_CONE;
    l.check_with(path, l.field, p.face_width_mm, &[re / 3.0], || {
        format!(
            "must be <= outer cone distance / 3, i.e. <= mean cone distance / 2.5 = {:.3} mm",
            p.mean_cone_distance_mm / 2.5
        )
    })
}

/// Both members' tooth numbers (the pinion's at most the wheel's) and
/// opposite hands.
fn check_teeth_and_hands(path: &Path, d: &DesignFile) -> Result<(), InputError> {
    for (name, m) in [("pinion", &d.pinion), ("wheel", &d.wheel)] {
        lim::TEETH.check_at(path, &format!("{name}.teeth"), m.teeth as f64)?;
        lim::PITCH_ANGLE.check_at(path, &format!("{name}.pitch_angle_deg"), m.pitch_angle_deg)?;
    }
    let l = &lim::PINION_TEETH;
    l.check_with(
        path,
        l.field,
        d.pinion.teeth as f64,
        &[d.wheel.teeth as f64],
        || format!("must be <= wheel.teeth = {}", d.wheel.teeth),
    )?;
    if d.pinion.hand == d.wheel.hand {
        let l = &lim::HAND;
        return Err(l.refuse(
            path,
            l.field,
            format!("{:?}", d.wheel.hand).to_lowercase(),
            "must be the opposite of pinion.hand".into(),
        ));
    }
    Ok(())
}

/// The pitch angles against the tooth numbers and the shaft angle, before
/// the root and face angles, whose limits they are; returns the pinion's
/// pitch angle from the tooth numbers, deg.
fn check_pitch_angles(path: &Path, d: &DesignFile) -> Result<f64, InputError> {
    let p = &d.pair;
    // Pitch angles from the tooth numbers and the shaft angle, before the
    // root and face angles, whose limits are the pitch angles: an
    // inconsistent pitch angle is reported as such.
    let sigma = p.shaft_angle_deg.to_radians();
    let g1 = pinion_pitch_angle(d.pinion.teeth as f64, d.wheel.teeth as f64, sigma).to_degrees();
    let g2 = p.shaft_angle_deg - g1;
    let tol = 0.01;
    if (d.pinion.pitch_angle_deg - g1).abs() > tol {
        let l = &lim::PINION_PITCH_ANGLE;
        return Err(l.refuse(
            path,
            l.field,
            d.pinion.pitch_angle_deg.to_string(),
            format!("must equal {g1:.4} (from the tooth numbers and shaft angle) within {tol}"),
        ));
    }
    if (d.wheel.pitch_angle_deg - g2).abs() > tol {
        let l = &lim::WHEEL_PITCH_ANGLE;
        return Err(l.refuse(
            path,
            l.field,
            d.wheel.pitch_angle_deg.to_string(),
            format!("must equal {g2:.4} (shaft angle minus pinion pitch angle) within {tol}"),
        ));
    }
    Ok(g1)
}

/// Each member's root and face angles, addendum and dedendum, point width
/// and material.
fn check_members(path: &Path, d: &DesignFile) -> Result<(), InputError> {
    let p = &d.pair;
    for (name, m) in [("pinion", &d.pinion), ("wheel", &d.wheel)] {
        let f = |s: &str| format!("{name}.{s}");
        let g = m.pitch_angle_deg;
        lim::ROOT_ANGLE.check_with(path, &f("root_angle_deg"), m.root_angle_deg, &[g], || {
            format!("must lie in [0.5, {g}] (at most {name}.pitch_angle_deg)")
        })?;
        lim::FACE_ANGLE.check_with(path, &f("face_angle_deg"), m.face_angle_deg, &[g], || {
            format!("must lie in [{g}, 89.9] (at least {name}.pitch_angle_deg)")
        })?;
        let depth = MAX_DEPTH_MODULES * p.mean_normal_module_mm;
        for (positive, deep, k, v) in [
            (
                &lim::ADDENDUM,
                &lim::ADDENDUM_DEPTH,
                "mean_addendum_mm",
                m.mean_addendum_mm,
            ),
            (
                &lim::DEDENDUM,
                &lim::DEDENDUM_DEPTH,
                "mean_dedendum_mm",
                m.mean_dedendum_mm,
            ),
        ] {
            positive.check_at(path, &f(k), v)?;
            deep.check_with(path, &f(k), v, &[depth], || {
                format!(
                    "must be <= {MAX_DEPTH_MODULES} m_n = {depth:.4} mm (m_n = pair.mean_normal_module_mm)"
                )
            })?;
        }
        // Addendum and dedendum shrink towards the toe (face and root cones
        // inclined to the pitch cone); at the toe the tip must still stand
        // above the pitch cone and the root below it, else the flank has no
        // addendum (or dedendum) part there.
        let half_face = 0.5 * p.face_width_mm;
        for (l, part, field, mean, angle, cone_angles, what) in [
            (
                &lim::ADDENDUM_AT_TOE,
                "addendum",
                "mean_addendum_mm",
                m.mean_addendum_mm,
                m.face_angle_deg - g,
                format!("{name}.face_angle_deg - {name}.pitch_angle_deg"),
                "the tip dips below the pitch cone there",
            ),
            (
                &lim::DEDENDUM_AT_TOE,
                "dedendum",
                "mean_dedendum_mm",
                m.mean_dedendum_mm,
                g - m.root_angle_deg,
                format!("{name}.pitch_angle_deg - {name}.root_angle_deg"),
                "the root rises above the pitch cone there",
            ),
        ] {
            let loss = half_face * angle.to_radians().tan();
            if mean - loss <= 0.0 {
                return Err(l.refuse(
                    path,
                    &f(field),
                    mean.to_string(),
                    format!(
                        "must exceed (pair.face_width_mm / 2) tan({cone_angles}) = {loss:.4} mm: the {part} at the toe is {:.4} mm, {what}",
                        mean - loss
                    ),
                ));
            }
        }
        for (l, k, v) in [
            (&lim::POINT_WIDTH, "point_width_mm", m.point_width_mm),
            (
                &lim::YOUNGS_MODULUS,
                "material.youngs_modulus_gpa",
                m.material.youngs_modulus_gpa,
            ),
            (
                &lim::POISSON_RATIO,
                "material.poisson_ratio",
                m.material.poisson_ratio,
            ),
            (
                &lim::DENSITY,
                "material.density_kg_m3",
                m.material.density_kg_m3,
            ),
        ] {
            l.check_at(path, &f(k), v)?;
        }
    }
    Ok(())
}

/// The mean normal module against the cone distance (`g1` the pinion's
/// pitch angle from the tooth numbers, deg), and the tip clearance of
/// both members.
fn check_module_and_clearance(path: &Path, d: &DesignFile, g1: f64) -> Result<(), InputError> {
    let p = &d.pair;
    // Mean normal module from the cone distance: m_n = 2 R_m sin γ₁ cos β / z₁.
    let mn = 2.0
        * p.mean_cone_distance_mm
        * g1.to_radians().sin()
        * p.mean_spiral_angle_deg.to_radians().cos()
        / d.pinion.teeth as f64;
    if (mn - p.mean_normal_module_mm).abs() > 2e-3 * mn {
        let l = &lim::NORMAL_MODULE_FROM_CONE;
        return Err(l.refuse(
            path,
            l.field,
            p.mean_normal_module_mm.to_string(),
            format!("must equal 2 R_m sin(γ1) cos(β) / z1 = {mn:.4} mm within 0.2%"),
        ));
    }
    // Clearance: each member's addendum below the mate's dedendum.
    for (a, b) in [("pinion", "wheel"), ("wheel", "pinion")] {
        let (ma, mb) = if a == "pinion" {
            (&d.pinion, &d.wheel)
        } else {
            (&d.wheel, &d.pinion)
        };
        lim::CLEARANCE.check_with(
            path,
            &format!("{a}.mean_addendum_mm"),
            ma.mean_addendum_mm,
            &[mb.mean_dedendum_mm],
            || {
                format!(
                    "must be < {b}.mean_dedendum_mm = {} (tip clearance)",
                    mb.mean_dedendum_mm
                )
            },
        )?;
    }
    Ok(())
}

/// The cutter's radius and edge radius, and the ease-off (with its
/// topography).
fn check_cutter_and_ease_off(path: &Path, d: &DesignFile) -> Result<(), InputError> {
    let p = &d.pair;
    let (r_min, r_max) = (
        MIN_CUTTER_RADIUS_CONE_DISTANCES * p.mean_cone_distance_mm,
        MAX_CUTTER_RADIUS_CONE_DISTANCES * p.mean_cone_distance_mm,
    );
    let l = &lim::CUTTER_RADIUS;
    l.check_with(path, l.field, d.cutter.radius_mm, &[r_min, r_max], || {
        format!(
            "must lie between the minimum and maximum [{MIN_CUTTER_RADIUS_CONE_DISTANCES}, {MAX_CUTTER_RADIUS_CONE_DISTANCES}] × pair.mean_cone_distance_mm = [{r_min:.1}, {r_max:.1}] mm (usual face-mill cutters: 0.5 to 1.5 R_m; beyond, the flanks cannot be generated)"
        )
    })?;
    let hi = 0.5 * d.pinion.point_width_mm.min(d.wheel.point_width_mm);
    let l = &lim::EDGE_RADIUS;
    l.check_with(path, l.field, d.cutter.edge_radius_mm, &[hi], || {
        format!("must lie in [0, {hi}]")
    })?;
    let e = &d.ease_off;
    for (l, v) in [
        (&lim::PROFILE_CROWNING, e.profile_crowning_um),
        (&lim::LENGTHWISE_CROWNING, e.lengthwise_crowning_um),
        (&lim::MOTION_ERROR, e.motion_error_urad),
        (&lim::BIAS, e.bias_um),
    ] {
        l.check(path, v)?;
    }
    if let Some(t) = &e.topography {
        check_topography(path, t)?;
    }
    Ok(())
}

fn check_topography(path: &Path, t: &TopographyDesign) -> Result<(), InputError> {
    for (nodes, node, order, v) in [
        (
            &lim::TOPOGRAPHY_PROFILE_NODES,
            &lim::TOPOGRAPHY_PROFILE,
            &lim::TOPOGRAPHY_PROFILE_ORDER,
            &t.profile,
        ),
        (
            &lim::TOPOGRAPHY_FACE_NODES,
            &lim::TOPOGRAPHY_FACE,
            &lim::TOPOGRAPHY_FACE_ORDER,
            &t.face,
        ),
    ] {
        let f = nodes.field;
        if !nodes.admits(v.len() as f64, &[]) {
            return Err(nodes.refuse(
                path,
                f,
                (v.len() as f64).to_string(),
                nodes.text_of_refusal(),
            ));
        }
        for (i, &x) in v.iter().enumerate() {
            node.check_at(path, &format!("{f}[{i}]"), x)?;
        }
        for (i, w) in v.windows(2).enumerate() {
            if w[1] <= w[0] {
                return Err(order.refuse(
                    path,
                    &format!("{f}[{}]", i + 1),
                    w[1].to_string(),
                    format!("must be strictly increasing (after {})", w[0]),
                ));
            }
        }
    }
    if t.deviation_um.len() != t.profile.len()
        || t.deviation_um.iter().any(|r| r.len() != t.face.len())
    {
        let l = &lim::TOPOGRAPHY_SHAPE;
        return Err(l.refuse(
            path,
            l.field,
            (t.deviation_um.len() as f64).to_string(),
            format!(
                "must have {} rows of {} values",
                t.profile.len(),
                t.face.len()
            ),
        ));
    }
    for (i, row) in t.deviation_um.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            lim::TOPOGRAPHY_DEVIATION.check_at(
                path,
                &format!("ease_off.topography.deviation_um[{i}][{j}]"),
                v,
            )?;
        }
    }
    Ok(())
}

/// Checks that need derived quantities: tooth thickness and the cutter circle.
fn check_derived(p: &PairData, path: &Path) -> Result<(), InputError> {
    for m in [Member::Pinion, Member::Wheel] {
        let s = p.normal_thickness(m);
        if s <= 0.0 {
            return Err(lim::TOOTH_LEFT.refuse(
                path,
                &format!("{}.point_width_mm", m.name()),
                (p.member(m).point_width * 1e3).to_string(),
                "leaves no tooth: point width + dedendum·(tan α_d + tan α_c) must be < π m_n"
                    .into(),
            ));
        }
    }
    let bl = p.normal_backlash();
    if bl < 0.0 {
        let l = &lim::BACKLASH;
        return Err(l.refuse(
            path,
            l.field,
            (p.members[1].point_width * 1e3).to_string(),
            format!(
                "teeth interfere: normal backlash π m_n − s_n1 − s_n2 = {:.4} mm must be >= 0",
                bl * 1e3
            ),
        ));
    }
    // The cutter circle through the mean point with the mean spiral angle must
    // reach toe and heel with a spiral angle below 90° on both sides of the slot.
    let min_r = min_cutter_radius(p);
    if p.cutter_radius < min_r {
        let l = &lim::CUTTER_CURVATURE;
        return Err(l.refuse(
            path,
            l.field,
            (p.cutter_radius * 1e3).to_string(),
            format!(
                "too small for the lengthwise curvature: the tooth trace must run from toe to heel with spiral angle in [-85°, 85°]; minimum is {:.2} mm",
                min_r * 1e3
            ),
        ));
    }
    Ok(())
}

/// Spiral angle along a cutter circle of radius `r` whose tangent at cone
/// distance `rm` makes the angle `beta` with the generatrix:
/// sin β(L) = (L² + r² − s²) / (2 L r), s² = R_m² − 2 R_m r sin β + r².
pub fn spiral_angle_at(rm: f64, beta: f64, r: f64, l: f64) -> Option<f64> {
    let s2 = rm * rm - 2.0 * rm * r * beta.sin() + r * r;
    let sb = (l * l + r * r - s2) / (2.0 * l * r);
    (sb.abs() <= 1.0).then(|| sb.asin())
}

fn trace_ok(p: &PairData, r: f64) -> bool {
    let limit = 85f64.to_radians();
    let slot = std::f64::consts::PI * p.normal_module - p.normal_thickness(Member::Pinion);
    [r - 0.5 * slot, r + 0.5 * slot].iter().all(|&rr| {
        rr > 0.0
            && [p.inner_cone_distance(), p.outer_cone_distance()]
                .iter()
                .all(|&l| {
                    spiral_angle_at(p.mean_cone_distance, p.spiral_angle, rr, l)
                        .is_some_and(|b| b.abs() <= limit)
                })
    })
}

/// Smallest cutter radius whose tooth traces satisfy [`trace_ok`] (bisection).
pub fn min_cutter_radius(p: &PairData) -> f64 {
    let (mut lo, mut hi) = (1e-6, 10.0 * p.outer_cone_distance());
    if trace_ok(p, lo) {
        return lo;
    }
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if trace_ok(p, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}
