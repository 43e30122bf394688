//! Gear pair design files (TOML, units in the field names) and their checks.
//!
//! A design file holds what a bevel gear designer has on the dimension sheet.
//! [`DesignFile::load`] parses it (unknown fields and malformed TOML are errors
//! with line and column) and [`DesignFile::to_pair`] checks it and converts it
//! to [`PairData`] in SI units. Every rejection names the file, the field, the
//! value and the limit.

use crate::error::InputError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Hand of spiral, seen from the face of the gear (from the cone apex side):
/// right hand when the outer half of the tooth turns clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Hand {
    Right,
    Left,
}

/// Top level of a design file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// Short name used in output paths.
    pub name: String,
    /// Where the data come from (paper, table).
    pub source: String,
    /// What was not published and was chosen, and why.
    #[serde(default)]
    pub notes: Vec<String>,
    pub pair: PairDesign,
    pub pinion: MemberDesign,
    pub wheel: MemberDesign,
    pub cutter: CutterDesign,
    #[serde(default)]
    pub ease_off: EaseOffDesign,
    /// Published results this pair is compared with. Not part of the
    /// geometry: [`geometry_text`] leaves this table out of what the meshes
    /// and stiffness files are hashed from.
    #[serde(default)]
    pub published: PublishedDesign,
}

/// Files of published results for this pair (TOML, paths relative to the
/// design file), for the report's comparison.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PublishedDesign {
    /// Loaded TE per blank and load (mean and peak-to-peak, multibody and
    /// NLFEA), e.g. the white paper's Tables 3–4.
    #[serde(default)]
    pub loaded_te: Option<PathBuf>,
    /// Run time per step or position, e.g. the white paper's Table 5.
    #[serde(default)]
    pub cpu: Option<PathBuf>,
}

/// The design file's text without its `[published]` table: what the pair's
/// geometry and material are read from (the hash of the meshes' inputs).
/// The table and the blank lines before it are cut up to the next table
/// header or the end, so adding it leaves the hash of a file unchanged.
pub fn geometry_text(text: &str) -> String {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let Some(start) = lines.iter().position(|l| l.trim() == "[published]") else {
        return text.to_string();
    };
    let end = (start + 1..lines.len())
        .find(|&i| lines[i].trim_start().starts_with('['))
        .unwrap_or(lines.len());
    let mut keep = start;
    while keep > 0 && lines[keep - 1].trim().is_empty() {
        keep -= 1;
    }
    let mut out: String = lines[..keep].concat();
    if end < lines.len() {
        out.push('\n');
        out.push_str(&lines[end..].concat());
    }
    out
}

/// Data common to both members.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairDesign {
    pub shaft_angle_deg: f64,
    pub mean_spiral_angle_deg: f64,
    pub mean_normal_module_mm: f64,
    pub mean_cone_distance_mm: f64,
    pub face_width_mm: f64,
    /// Normal pressure angle of the drive side (pinion concave, wheel convex).
    pub drive_pressure_angle_deg: f64,
    /// Normal pressure angle of the coast side (pinion convex, wheel concave).
    pub coast_pressure_angle_deg: f64,
}

/// Data of one member.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberDesign {
    pub teeth: u32,
    pub hand: Hand,
    pub pitch_angle_deg: f64,
    pub root_angle_deg: f64,
    pub face_angle_deg: f64,
    /// Addendum at the mean cone distance, measured normal to the pitch cone.
    pub mean_addendum_mm: f64,
    /// Dedendum at the mean cone distance, measured normal to the pitch cone.
    pub mean_dedendum_mm: f64,
    /// Point width of the blades that cut this member's slots (normal section, blade tips).
    pub point_width_mm: f64,
    pub material: MaterialDesign,
}

/// Linear elastic material, as the design file gives it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesign {
    pub youngs_modulus_gpa: f64,
    pub poisson_ratio: f64,
    pub density_kg_m3: f64,
}

/// The face-mill cutter of the generating crown gear.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutterDesign {
    /// Mean (nominal) cutter radius: centre of the pinion slot at the pitch plane.
    pub radius_mm: f64,
    /// Blade edge radius that cuts the root fillet.
    pub edge_radius_mm: f64,
}

/// Flank modification (ease-off) designed on the pinion, as normal deviations
/// from the conjugate flank (positive = material removed).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseOffDesign {
    /// Deviation at the tip and root limits of the active profile, relative to its middle.
    #[serde(default)]
    pub profile_crowning_um: f64,
    /// Deviation at toe and heel, relative to the mean point.
    #[serde(default)]
    pub lengthwise_crowning_um: f64,
    /// Flank twist: deviation at heel-tip (positive) and toe-tip (negative) corners.
    #[serde(default)]
    pub bias_um: f64,
    /// Parabolic motion error: wheel-side transmission error reached half a
    /// mesh cycle away from the parabola's vertex.
    #[serde(default)]
    pub motion_error_urad: f64,
    /// Measured or imported topography added on top (normal deviations on a grid).
    #[serde(default)]
    pub topography: Option<TopographyDesign>,
}

/// Normal deviations on a grid in normalised flank coordinates (profile 0 = root
/// limit of the flank, 1 = tip; face 0 = toe, 1 = heel), bicubic between nodes.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopographyDesign {
    /// Strictly increasing profile coordinates in [0, 1].
    pub profile: Vec<f64>,
    /// Strictly increasing face coordinates in [0, 1].
    pub face: Vec<f64>,
    /// `deviation_um[i][j]` at (profile[i], face[j]).
    pub deviation_um: Vec<Vec<f64>>,
}

/// Which member.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Member {
    Pinion,
    Wheel,
}

impl Member {
    pub fn name(self) -> &'static str {
        match self {
            Member::Pinion => "pinion",
            Member::Wheel => "wheel",
        }
    }
}

/// Checked design data in SI units (m, rad, Pa).
#[derive(Debug, Clone, Serialize)]
pub struct PairData {
    pub name: String,
    pub shaft_angle: f64,
    pub spiral_angle: f64,
    pub normal_module: f64,
    pub mean_cone_distance: f64,
    pub face_width: f64,
    /// Normal pressure angle, index 0 = drive side, 1 = coast side.
    pub pressure_angle: [f64; 2],
    pub members: [MemberData; 2],
    pub cutter_radius: f64,
    pub edge_radius: f64,
    pub ease_off: EaseOffDesign,
    /// Published results, paths resolved against the design file's folder.
    pub published: PublishedDesign,
}

/// One member, SI.
#[derive(Debug, Clone, Serialize)]
pub struct MemberData {
    pub teeth: u32,
    pub hand: Hand,
    pub pitch_angle: f64,
    pub root_angle: f64,
    pub face_angle: f64,
    pub mean_addendum: f64,
    pub mean_dedendum: f64,
    pub point_width: f64,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub density: f64,
}

impl MemberData {
    /// The member's elastic constants.
    pub fn material(&self) -> crate::Material {
        crate::Material {
            youngs_modulus_pa: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }
}

impl PairData {
    pub fn member(&self, m: Member) -> &MemberData {
        match m {
            Member::Pinion => &self.members[0],
            Member::Wheel => &self.members[1],
        }
    }
    /// Outer (heel) and inner (toe) cone distances.
    pub fn outer_cone_distance(&self) -> f64 {
        self.mean_cone_distance + 0.5 * self.face_width
    }
    pub fn inner_cone_distance(&self) -> f64 {
        self.mean_cone_distance - 0.5 * self.face_width
    }
    /// Mean normal circular tooth thickness at the pitch cone, from the point
    /// width: slot = W + h_f (tan α_d + tan α_c), thickness = π m_n − slot.
    pub fn normal_thickness(&self, m: Member) -> f64 {
        let d = self.member(m);
        let slot = d.point_width
            + d.mean_dedendum * (self.pressure_angle[0].tan() + self.pressure_angle[1].tan());
        std::f64::consts::PI * self.normal_module - slot
    }
    /// Normal backlash at the mean point: π m_n − s_n1 − s_n2.
    pub fn normal_backlash(&self) -> f64 {
        std::f64::consts::PI * self.normal_module
            - self.normal_thickness(Member::Pinion)
            - self.normal_thickness(Member::Wheel)
    }
    /// Number of teeth of the virtual generating crown gear, z / sin γ.
    pub fn crown_teeth(&self) -> f64 {
        self.members[0].teeth as f64 / self.members[0].pitch_angle.sin()
    }
    /// Pinion rotation of one mesh cycle, 2π / z₁.
    pub fn mesh_cycle(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.members[0].teeth as f64
    }
}

impl DesignFile {
    /// Reads and parses a design file (no semantic checks yet).
    pub fn load(path: &Path) -> Result<Self, InputError> {
        let text = std::fs::read_to_string(path).map_err(|e| InputError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
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

struct Checker<'a> {
    path: &'a Path,
}

impl Checker<'_> {
    fn fail(&self, field: &str, value: f64, limit: String) -> InputError {
        InputError::Invalid {
            path: PathBuf::from(self.path),
            field: field.to_string(),
            value: format!("{value}"),
            limit,
        }
    }
    fn positive(&self, field: &str, v: f64) -> Result<(), InputError> {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(self.fail(field, v, "must be > 0".into()))
        }
    }
    fn range(&self, field: &str, v: f64, lo: f64, hi: f64) -> Result<(), InputError> {
        if v.is_finite() && v >= lo && v <= hi {
            Ok(())
        } else {
            Err(self.fail(field, v, format!("must lie in [{lo}, {hi}]")))
        }
    }
}

/// Pitch cone angle of the pinion from the tooth numbers and shaft angle:
/// tan γ₁ = sin Σ / (z₂/z₁ + cos Σ).
pub fn pinion_pitch_angle(z1: f64, z2: f64, shaft_angle: f64) -> f64 {
    (shaft_angle.sin() / (z2 / z1 + shaft_angle.cos())).atan()
}

fn check_design(d: &DesignFile, path: &Path) -> Result<(), InputError> {
    let c = Checker { path };
    let p = &d.pair;
    c.range("pair.shaft_angle_deg", p.shaft_angle_deg, 30.0, 150.0)?;
    c.range(
        "pair.mean_spiral_angle_deg",
        p.mean_spiral_angle_deg,
        0.0,
        50.0,
    )?;
    c.positive("pair.mean_normal_module_mm", p.mean_normal_module_mm)?;
    c.positive("pair.mean_cone_distance_mm", p.mean_cone_distance_mm)?;
    c.positive("pair.face_width_mm", p.face_width_mm)?;
    c.range(
        "pair.drive_pressure_angle_deg",
        p.drive_pressure_angle_deg,
        10.0,
        35.0,
    )?;
    c.range(
        "pair.coast_pressure_angle_deg",
        p.coast_pressure_angle_deg,
        10.0,
        35.0,
    )?;
    // Usual limit: face width at most a third of the outer cone distance.
    let re = p.mean_cone_distance_mm + 0.5 * p.face_width_mm;
    if p.face_width_mm > re / 3.0 {
        return Err(c.fail(
            "pair.face_width_mm",
            p.face_width_mm,
            format!(
                "must be <= outer cone distance / 3, i.e. <= mean cone distance / 2.5 = {:.3} mm",
                p.mean_cone_distance_mm / 2.5
            ),
        ));
    }
    for (name, m) in [("pinion", &d.pinion), ("wheel", &d.wheel)] {
        let f = |s: &str| format!("{name}.{s}");
        if m.teeth < 5 {
            return Err(c.fail(&f("teeth"), m.teeth as f64, "must be >= 5".into()));
        }
        c.range(&f("pitch_angle_deg"), m.pitch_angle_deg, 1.0, 89.0)?;
        c.range(
            &f("root_angle_deg"),
            m.root_angle_deg,
            0.5,
            m.pitch_angle_deg,
        )?;
        c.range(
            &f("face_angle_deg"),
            m.face_angle_deg,
            m.pitch_angle_deg,
            89.9,
        )?;
        c.positive(&f("mean_addendum_mm"), m.mean_addendum_mm)?;
        c.positive(&f("mean_dedendum_mm"), m.mean_dedendum_mm)?;
        c.positive(&f("point_width_mm"), m.point_width_mm)?;
        c.range(
            &f("material.youngs_modulus_gpa"),
            m.material.youngs_modulus_gpa,
            1.0,
            1000.0,
        )?;
        c.range(
            &f("material.poisson_ratio"),
            m.material.poisson_ratio,
            0.0,
            0.49,
        )?;
        c.positive(&f("material.density_kg_m3"), m.material.density_kg_m3)?;
    }
    if d.pinion.teeth > d.wheel.teeth {
        return Err(c.fail(
            "pinion.teeth",
            d.pinion.teeth as f64,
            format!("must be <= wheel.teeth = {}", d.wheel.teeth),
        ));
    }
    if d.pinion.hand == d.wheel.hand {
        return Err(InputError::Invalid {
            path: path.to_path_buf(),
            field: "wheel.hand".into(),
            value: format!("{:?}", d.wheel.hand).to_lowercase(),
            limit: "must be the opposite of pinion.hand".into(),
        });
    }
    // Pitch angles from the tooth numbers and the shaft angle.
    let sigma = p.shaft_angle_deg.to_radians();
    let g1 = pinion_pitch_angle(d.pinion.teeth as f64, d.wheel.teeth as f64, sigma).to_degrees();
    let g2 = p.shaft_angle_deg - g1;
    let tol = 0.01;
    if (d.pinion.pitch_angle_deg - g1).abs() > tol {
        return Err(c.fail(
            "pinion.pitch_angle_deg",
            d.pinion.pitch_angle_deg,
            format!("must equal {g1:.4} (from the tooth numbers and shaft angle) within {tol}"),
        ));
    }
    if (d.wheel.pitch_angle_deg - g2).abs() > tol {
        return Err(c.fail(
            "wheel.pitch_angle_deg",
            d.wheel.pitch_angle_deg,
            format!("must equal {g2:.4} (shaft angle minus pinion pitch angle) within {tol}"),
        ));
    }
    // Mean normal module from the cone distance: m_n = 2 R_m sin γ₁ cos β / z₁.
    let mn = 2.0
        * p.mean_cone_distance_mm
        * g1.to_radians().sin()
        * p.mean_spiral_angle_deg.to_radians().cos()
        / d.pinion.teeth as f64;
    if (mn - p.mean_normal_module_mm).abs() > 2e-3 * mn {
        return Err(c.fail(
            "pair.mean_normal_module_mm",
            p.mean_normal_module_mm,
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
        if ma.mean_addendum_mm >= mb.mean_dedendum_mm {
            return Err(c.fail(
                &format!("{a}.mean_addendum_mm"),
                ma.mean_addendum_mm,
                format!(
                    "must be < {b}.mean_dedendum_mm = {} (tip clearance)",
                    mb.mean_dedendum_mm
                ),
            ));
        }
    }
    c.positive("cutter.radius_mm", d.cutter.radius_mm)?;
    c.range(
        "cutter.edge_radius_mm",
        d.cutter.edge_radius_mm,
        0.0,
        0.5 * d.pinion.point_width_mm.min(d.wheel.point_width_mm),
    )?;
    let e = &d.ease_off;
    for (f, v) in [
        ("ease_off.profile_crowning_um", e.profile_crowning_um),
        ("ease_off.lengthwise_crowning_um", e.lengthwise_crowning_um),
        ("ease_off.motion_error_urad", e.motion_error_urad),
    ] {
        c.range(f, v, 0.0, 500.0)?;
    }
    c.range("ease_off.bias_um", e.bias_um, -500.0, 500.0)?;
    if let Some(t) = &e.topography {
        check_topography(&c, t)?;
    }
    Ok(())
}

fn check_topography(c: &Checker, t: &TopographyDesign) -> Result<(), InputError> {
    for (f, v) in [
        ("ease_off.topography.profile", &t.profile),
        ("ease_off.topography.face", &t.face),
    ] {
        if v.len() < 2 {
            return Err(c.fail(f, v.len() as f64, "needs at least 2 nodes".into()));
        }
        for w in v.windows(2) {
            if w[1] <= w[0] {
                return Err(c.fail(
                    f,
                    w[1],
                    format!("must be strictly increasing (after {})", w[0]),
                ));
            }
        }
        if v[0] < 0.0 || v[v.len() - 1] > 1.0 {
            return Err(c.fail(f, v[0].min(v[v.len() - 1]), "must lie in [0, 1]".into()));
        }
    }
    if t.deviation_um.len() != t.profile.len()
        || t.deviation_um.iter().any(|r| r.len() != t.face.len())
    {
        return Err(c.fail(
            "ease_off.topography.deviation_um",
            t.deviation_um.len() as f64,
            format!(
                "must have {} rows of {} values",
                t.profile.len(),
                t.face.len()
            ),
        ));
    }
    Ok(())
}

/// Checks that need derived quantities: tooth thickness and the cutter circle.
fn check_derived(p: &PairData, path: &Path) -> Result<(), InputError> {
    let c = Checker { path };
    for m in [Member::Pinion, Member::Wheel] {
        let s = p.normal_thickness(m);
        if s <= 0.0 {
            let f = format!("{}.point_width_mm", m.name());
            return Err(c.fail(
                &f,
                p.member(m).point_width * 1e3,
                "leaves no tooth: point width + dedendum·(tan α_d + tan α_c) must be < π m_n"
                    .into(),
            ));
        }
    }
    let bl = p.normal_backlash();
    if bl < 0.0 {
        return Err(c.fail(
            "wheel.point_width_mm",
            p.members[1].point_width * 1e3,
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
        return Err(c.fail(
            "cutter.radius_mm",
            p.cutter_radius * 1e3,
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
