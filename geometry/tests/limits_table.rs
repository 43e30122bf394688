//! The table of `docs/limits.md` is the one the checks' own entries
//! generate (`geometry::limits::markdown_table`), and every numeric limit
//! in it is enforced: a value just beyond each end (and NaN) is refused
//! naming the field, a value at or just inside an end is not refused by
//! that limit. With `BLESS=1` the first test writes the file instead.

mod common;

use geometry::design::DesignFile;
use geometry::error::InputError;
use geometry::limits::{self, End, File, Limit, Number, Range, Rule, Says};
use geometry::scene::Scene;
use std::path::{Path, PathBuf};
use toml::Value;

/// What `docs/limits.md` holds above the table.
const HEADER: &str = "# Limits of the scene and design fields

Every limit the scene and design checks enforce, one row per rule: the file
the field lives in, the field as a refusal names it, the rule, the unit and
why (where the code gives a reason). `<member>` stands for `pinion` or
`wheel` and `<mate>` for the other one, `<level>` for a mesh level
(`reduced_order`, `medium`, `reference`), `[i]` and `[j]` for an index.
Every number of a range must also be finite (NaN and ±∞ are refused).
Other fields in a rule are named in backticks; derived limits are computed
from the design or other fields, and their refusals give the value.

The table is generated from the entries the checks test values against
(`geometry::limits::markdown_table`, `geometry/src/limits/`), and
`geometry/tests/limits_table.rs` checks that this file is that table and
that each numeric limit refuses a value just beyond it. After changing a
limit, regenerate the file with
`BLESS=1 cargo test -p geometry --test limits_table`.

";

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

#[test]
fn limits_table_in_docs_is_the_one_the_checks_generate() {
    let path = root().join("docs/limits.md");
    let want = format!("{HEADER}{}", limits::markdown_table());
    if std::env::var_os("BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, &want).unwrap();
        return;
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "docs/limits.md is not the table the checks generate; regenerate it with BLESS=1 cargo test -p geometry --test limits_table"
    );
}

#[test]
fn the_table_has_a_row_per_entry_scene_before_design() {
    let table = limits::markdown_table();
    let rows: Vec<&str> = table.lines().skip(2).collect();
    assert_eq!(rows.len(), limits::all().count());
    let first_design = rows.iter().position(|r| r.starts_with("| design |"));
    let last_scene = rows.iter().rposition(|r| r.starts_with("| scene |"));
    assert!(last_scene < first_design, "{table}");
    // Every row has its five cells (no unescaped '|' inside one).
    for r in &rows {
        let cells = r.replace("\\|", "").matches('|').count();
        assert_eq!(cells, 6, "{r}");
    }
}

/// The forms a number takes in a message: as written, as 1e6, with
/// thousands separators, in words.
fn number_forms(v: f64) -> Vec<String> {
    let v = v.abs();
    let plain = v.to_string();
    let mut grouped = String::new();
    for (i, c) in plain.chars().enumerate() {
        if i > 0 && (plain.len() - i) % 3 == 0 && !plain.contains('.') {
            grouped.push(',');
        }
        grouped.push(c);
    }
    let word = match v {
        1.0 => "one",
        2.0 => "two",
        _ => "",
    };
    vec![plain, format!("{v:e}"), grouped, word.into()]
}

#[test]
fn every_refusal_text_states_the_numbers_of_its_range() {
    for l in limits::all() {
        let Some(r) = l.range() else { continue };
        let nums: Vec<f64> = [r.lo, r.hi]
            .iter()
            .filter_map(|e| match *e {
                End::Num { value, .. } => Some(value),
                _ => None,
            })
            .collect();
        match r.says {
            Says::LieIn(_) | Says::EachLieIn(_) => assert_eq!(
                nums.len(),
                2,
                "{}: \"must lie in\" needs numbers at both ends",
                l.field
            ),
            Says::Text(t) => {
                for v in nums {
                    assert!(
                        number_forms(v).iter().any(|f| t.contains(f.as_str())),
                        "{}: '{t}' does not state {v}",
                        l.field
                    );
                }
            }
            Says::Computed => {}
        }
    }
}

/// A step of a field's path: a key or an index.
enum Seg {
    Key(String),
    Index(usize),
}

/// `a.b[0].c` or `m[0][1]` as its steps.
fn segments(path: &str) -> Vec<Seg> {
    let mut segs = Vec::new();
    for part in path.split('.') {
        let (key, rest) = part.split_once('[').unwrap_or((part, ""));
        segs.push(Seg::Key(key.into()));
        for i in rest.split('[').filter(|s| !s.is_empty()) {
            segs.push(Seg::Index(i.trim_end_matches(']').parse().unwrap()));
        }
    }
    segs
}

/// The value at `path`, if there is one.
fn get<'a>(doc: &'a Value, path: &str) -> Option<&'a Value> {
    segments(path).iter().try_fold(doc, |v, s| match s {
        Seg::Key(k) => v.get(k.as_str()),
        Seg::Index(i) => v.get(*i),
    })
}

/// Replaces the value at `segs` (created with its tables where missing)
/// by `op(old)`; a key met in an array of tables is set in every table.
fn set(v: &mut Value, segs: &[Seg], op: &dyn Fn(Option<&Value>) -> Value) {
    if let Value::Array(a) = v {
        if let Some(Seg::Key(_)) = segs.first() {
            for t in a {
                set(t, segs, op);
            }
            return;
        }
    }
    match (&segs[0], segs.len()) {
        (Seg::Key(k), 1) => {
            let t = v.as_table_mut().expect("a table");
            let new = op(t.get(k.as_str()));
            t.insert(k.clone(), new);
        }
        (Seg::Key(k), _) => {
            let t = v.as_table_mut().expect("a table");
            let next = t
                .entry(k.clone())
                .or_insert_with(|| Value::Table(Default::default()));
            set(next, &segs[1..], op);
        }
        (Seg::Index(i), 1) => {
            let a = v.as_array_mut().expect("an array");
            a[*i] = op(Some(&a[*i]));
        }
        (Seg::Index(i), _) => set(&mut v.as_array_mut().expect("an array")[*i], &segs[1..], op),
    }
}

/// `add`'s tables merged into `base`, its values replacing base's.
fn merge(base: &mut Value, add: Value) {
    match (base, add) {
        (Value::Table(b), Value::Table(a)) => {
            for (k, v) in a {
                match b.get_mut(&k) {
                    Some(old) => merge(old, v),
                    None => {
                        b.insert(k, v);
                    }
                }
            }
        }
        (b, a) => *b = a,
    }
}

fn parse(text: &str) -> Value {
    Value::Table(toml::from_str(text).unwrap())
}

/// Tables a field needs that the default scene does not have, by the
/// start of the field's path.
const SCENE_TABLES: &[(&str, &str)] = &[
    ("mesh.medium", "[mesh]\nmedium = { profile = 20, face = 39 }\n"),
    ("multibody.runup_rpm", "[multibody]\nrunup_rpm = [0.0, 1000.0]\n"),
    (
        "multibody.impact",
        "[multibody]\nforce_law = \"impact\"\n[multibody.impact]\nstiffness_n_per_mm_e = 1e5\nstiction_speed_mm_s = 100.0\nfriction_transition_speed_mm_s = 1000.0\n",
    ),
    (
        "multibody.load_run",
        "[multibody.load_run]\npinion_rpm = 1000.0\npinion_ramp_s = 0.01\nwheel_torque_nm = 100.0\nwheel_torque_rise_s = 0.01\ntime_s = 0.1\nmax_step_s = 1e-5\nsteady_from_s = 0.05\noutput_interval_s = 1e-3\n",
    ),
    (
        "multibody.ste_dte",
        "[multibody.ste_dte]\nwheel_blanks = [\"standard\"]\npinion_torque_nm = 300.0\nrpm = [10.0, 1000.0]\nacceleration_end_deg = 30.0\ntime_s = 0.15\nmax_step_s = 1e-5\ncompared_revolutions = 1.0\n",
    ),
    (
        "bearings",
        "[bearings]
tolerance_nm = 1.0
max_iterations = 60
pinion = [
  { axial_position_mm = 110.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 5e8, radial_damping_n_s_per_m = 100.0, axial_damping_n_s_per_m = 100.0 },
  { axial_position_mm = 170.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 0.0 },
]
wheel = [
  { axial_position_mm = 60.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 5e8, radial_damping_n_s_per_m = 100.0, axial_damping_n_s_per_m = 100.0 },
  { axial_position_mm = 140.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 0.0 },
]
pinion_body = { mass_kg = 5.0, centroid_mm = 120.0, transverse_inertia_kgm2 = 0.02 }
wheel_body = { mass_kg = 12.0, centroid_mm = 60.0, transverse_inertia_kgm2 = 0.1 }
[bearings.pinion_shaft]
seat_mm = 100.0
segments = [ { from_mm = 100.0, to_mm = 180.0, outer_diameter_mm = 40.0, inner_diameter_mm = 10.0 } ]
[bearings.wheel_shaft]
seat_mm = 60.0
segments = [ { from_mm = 50.0, to_mm = 150.0, outer_diameter_mm = 60.0, inner_diameter_mm = 10.0 } ]
[bearings.gearbox]
shaft_element_mm = 10.0
modes_up_to_hz = 5000.0
[bearings.gearbox.housing]
pinion_bore_diameter_mm = 80.0
wheel_bore_diameter_mm = 90.0
wall_mm = 15.0
floor_mm = 20.0
rim_mm = 20.0
clearance_mm = 10.0
foot_mm = 50.0
element_mm = 10.0
modes_up_to_hz = 10000.0
youngs_modulus_gpa = 110.0
poisson_ratio = 0.26
density_kg_m3 = 7200.0
damping_ratio = 0.02
",
    ),
    (
        "lumped",
        "[lumped]
mesh_cycles = 50.0
dropped_mesh_cycles = 10.0
more_pinion_torques_nm = [200.0]
pinion_bearing_stiffness_n_per_m = [1e9, 1e9, 1e9]
wheel_bearing_stiffness_n_per_m = [1e9, 1e9, 1e9]
[lumped.friction]
base_coefficient = 0.1
roughness_coefficient_per_um = 0.05
[lumped.roughness]
ra_um = [0.4]
seed = 1
profile_nodes = 20
face_nodes = 20
[[lumped.design_variants]]
name = \"a\"
te_slope_m21 = -0.001
profile_crowning_um = 5.0
lengthwise_crowning_um = 10.0
[lumped.order_map]
pinion_speeds_rpm = [1000.0]
wheel_revolutions = 3.0
dropped_wheel_revolutions = 1.0
max_pinion_order = 50.0
",
    ),
    (
        "sensitivity",
        "[sensitivity]\nvalues = 9\noffset_mm = 0.05\npinion_axial_mm = 0.05\nwheel_axial_mm = 0.05\nshaft_angle_deg = 0.02\n",
    ),
];

/// The same for the white-paper design.
const DESIGN_TABLES: &[(&str, &str)] = &[
    (
        "ease_off.topography",
        "[ease_off.topography]\nprofile = [0.0, 0.5, 1.0]\nface = [0.0, 0.5, 1.0]\ndeviation_um = [[0.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 0.0]]\n",
    ),
    (
        "machine_settings",
        concat!(
            "[machine_settings.pinion.concave]\nblade_radius_mm = 117.134116\nblade_angle_deg = 20.0\nradial_setting_mm = 115.468611\ncradle_angle_deg = -59.348062\nmachine_root_angle_deg = 24.943905\nratio_of_roll = 2.371181\n",
            "[machine_settings.pinion.convex]\nblade_radius_mm = 111.465884\nblade_angle_deg = 20.0\nradial_setting_mm = 112.976894\ncradle_angle_deg = -52.369927\nmachine_root_angle_deg = 24.943905\nratio_of_roll = 2.371181\n",
            "[machine_settings.wheel.concave]\nblade_radius_mm = 111.465884\nblade_angle_deg = 20.0\nradial_setting_mm = 112.976894\ncradle_angle_deg = -59.904597\nmachine_root_angle_deg = 65.056095\nratio_of_roll = 1.102875\n",
            "[machine_settings.wheel.convex]\nblade_radius_mm = 117.134116\nblade_angle_deg = 20.0\nradial_setting_mm = 115.468611\ncradle_angle_deg = -59.348062\nmachine_root_angle_deg = 65.056095\nratio_of_roll = 1.102875\n",
        ),
    ),
];

/// The default scene (its design path absolute) and the white-paper
/// design as TOML values, and a folder to load them from.
struct Files {
    scene: Value,
    design: Value,
    dir: tempfile::TempDir,
    /// Files loaded.
    loads: std::cell::Cell<usize>,
}

impl Files {
    fn new() -> Self {
        let mut scene =
            parse(&std::fs::read_to_string(common::reference("scenes/default.toml")).unwrap());
        set(&mut scene, &segments("design"), &|_| {
            Value::String(common::white_paper_path().display().to_string())
        });
        let design = parse(&std::fs::read_to_string(common::white_paper_path()).unwrap());
        Files {
            scene,
            design,
            dir: tempfile::tempdir().unwrap(),
            loads: Default::default(),
        }
    }

    /// The file of `l` with the tables field `at` needs.
    fn base(&self, l: &Limit, at: &str) -> Value {
        let (mut doc, tables) = match l.file {
            File::Scene => (self.scene.clone(), SCENE_TABLES),
            File::Design => (self.design.clone(), DESIGN_TABLES),
        };
        for (start, text) in tables {
            if at.starts_with(start) {
                merge(&mut doc, parse(text));
            }
        }
        doc
    }

    /// Loads `doc` as the file of `l`: the scene with its design, or the
    /// design alone (every check of [`DesignFile::to_pair`]).
    fn load(&self, l: &Limit, doc: &Value) -> Result<(), InputError> {
        let text = toml::to_string(doc).unwrap();
        self.loads.set(self.loads.get() + 1);
        match l.file {
            File::Scene => {
                let path = self.dir.path().join("scene.toml");
                std::fs::write(&path, text).unwrap();
                Scene::load(&path).map(|_| ())
            }
            File::Design => {
                let path = Path::new("design.toml");
                DesignFile::parse(&text, path).and_then(|d| d.to_pair(path).map(|_| ()))
            }
        }
    }
}

/// The fields a pattern stands for, each with its member (for `<member>`
/// and `<mate>` in the ends): every member and mesh level, index 0.
fn instances(field: &str) -> Vec<(String, Option<&'static str>)> {
    let field = field.replace("[i]", "[0]").replace("[j]", "[0]");
    let mut out = Vec::new();
    if field.contains("<flank>") {
        for (m, _) in instances(&field.replace("<flank>", "concave")) {
            let member = m.split('.').nth(1).and_then(|m| match m {
                "pinion" => Some("pinion"),
                "wheel" => Some("wheel"),
                _ => None,
            });
            out.push((m.clone(), member));
            out.push((m.replace(".concave.", ".convex."), member));
        }
    } else if field.contains("<member>") {
        for (m, mate) in [("pinion", "wheel"), ("wheel", "pinion")] {
            out.push((
                field.replace("<member>", m).replace("<mate>", mate),
                Some(m),
            ));
        }
    } else if field.contains("<level>") {
        for level in ["reduced_order", "reference", "medium"] {
            out.push((field.replace("<level>", level), None));
        }
    } else {
        out.push((field, None));
    }
    out
}

/// `field` with `<member>` and `<mate>` for `member`.
fn for_member(field: &str, member: Option<&str>) -> String {
    match member {
        Some(m) => {
            let mate = if m == "pinion" { "wheel" } else { "pinion" };
            field.replace("<member>", m).replace("<mate>", mate)
        }
        None => field.into(),
    }
}

/// The next float from `x` upward or downward.
fn next(x: f64, up: bool) -> f64 {
    if x == 0.0 {
        let tiny = f64::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let b = x.to_bits();
    f64::from_bits(if (x > 0.0) == up { b + 1 } else { b - 1 })
}

/// An end as a value: (value, closed, exactly a number of the entry).
fn end_value(end: &End, docs: [&Value; 2], member: Option<&str>) -> Option<(f64, bool, bool)> {
    match *end {
        End::Unbounded | End::Derived { .. } => None,
        End::Num { value, closed, .. } => Some((value, closed, true)),
        End::Field {
            field,
            scale,
            offset,
            closed,
        } => {
            let field = for_member(field, member);
            let v = docs
                .iter()
                .find_map(|d| get(d, &field))
                .unwrap_or_else(|| panic!("{field}: not in the scene or the design"));
            let v = v
                .as_float()
                .or(v.as_integer().map(|i| i as f64))
                .unwrap_or_else(|| panic!("{field} = {v}: not a number"));
            Some((scale * v + offset, closed, false))
        }
    }
}

/// Whether the field is a TOML path the test can set.
fn is_path(field: &str) -> bool {
    !field.contains(' ')
}

/// One probe of a field: a value (or a number of entries) written into
/// its file, and the outcome.
struct Probe<'a> {
    files: &'a Files,
    limit: &'a Limit,
    range: &'a Range,
    field: &'a str,
    failures: &'a mut Vec<String>,
}

impl Probe<'_> {
    /// Loads the file with the field set to `v`.
    fn load(&mut self, v: f64) -> Result<(), InputError> {
        let mut doc = self.files.base(self.limit, self.field);
        let r = self.range;
        let list_mismatch = std::cell::Cell::new(false);
        let op = |old: Option<&Value>| -> Value {
            let number = match r.number {
                Number::Real => Value::Float(v),
                _ => Value::Integer(v as i64),
            };
            match (r.number, old) {
                (Number::Count, Some(Value::Array(a))) => {
                    Value::Array(vec![a[0].clone(); v as usize])
                }
                (Number::Count, _) => panic!("a count needs its list in the file"),
                (_, Some(Value::Array(a))) => {
                    list_mismatch.set(!r.list);
                    Value::Array(a.iter().map(|_| number.clone()).collect())
                }
                _ => {
                    list_mismatch.set(r.list);
                    number
                }
            }
        };
        set(&mut doc, &segments(self.field), &op);
        if list_mismatch.get() {
            self.failures.push(format!(
                "{}: the file's value and the entry disagree on whether it is a list",
                self.field
            ));
        }
        self.files.load(self.limit, &doc)
    }

    /// `v` must be refused naming the field; returns the refusal's text.
    fn refused(&mut self, v: f64, what: &str) -> Option<String> {
        match self.load(v) {
            Err(InputError::Invalid { field, limit, .. }) if field == self.field => Some(limit),
            other => {
                self.failures.push(format!(
                    "{} = {v} ({what}): must be refused naming the field, got {}",
                    self.field,
                    outcome(&other)
                ));
                None
            }
        }
    }

    /// `v` must not be refused by this limit, whose refusal at this end
    /// says `said`: it loads, or another field or another rule of this
    /// field refuses it.
    fn not_refused(&mut self, v: f64, said: &str, what: &str) {
        match self.load(v) {
            Ok(()) => {}
            Err(InputError::Invalid { field, .. }) if field != self.field => {}
            Err(InputError::Invalid { limit, .. }) if limit != said => {}
            other => self.failures.push(format!(
                "{} = {v} ({what}): must not be refused by {}, got {}",
                self.field,
                self.limit.rule_text(),
                outcome(&other)
            )),
        }
    }
}

fn outcome(r: &Result<(), InputError>) -> String {
    match r {
        Ok(()) => "loaded".into(),
        Err(e) => e.to_string(),
    }
}

/// Numeric entries the test cannot drive through a field: each bounds a
/// quantity derived from a step (positions, time steps; driven in
/// `input_limits.rs`) or a product of two fields.
const UNDRIVEN: &[&str] = &[
    "rotation.step_deg",
    "utca.step_deg",
    "stiffness.grid_profile × stiffness.grid_face",
    "multibody.quasi_static_max_step_s",
    "multibody.runup_max_step_s",
    "multibody.table_step_deg",
    "multibody.rattle_max_step_s",
    "multibody.ste_dte.time_s",
    "multibody.ste_dte.max_step_s",
    "multibody.ste_dte.compared_revolutions",
    "multibody.load_run.max_step_s",
];

#[test]
fn every_numeric_limit_refuses_a_value_just_beyond_it_naming_the_field() {
    let files = Files::new();
    for (l, tables) in [
        (&limits::scene::NAME, SCENE_TABLES),
        (&limits::design::NAME, DESIGN_TABLES),
    ] {
        files
            .load(l, &files.base(l, ""))
            .expect("the default files load");
        for (start, _) in tables {
            files
                .load(l, &files.base(l, start))
                .unwrap_or_else(|e| panic!("with the tables of {start}: {e}"));
        }
    }
    let mut failures = Vec::new();
    let mut undriven = Vec::new();
    let mut driven = 0;
    for l in limits::all() {
        let Rule::Range(r) = &l.rule else { continue };
        if r.quantity.is_some() || !is_path(l.field) {
            undriven.push(l.field);
            continue;
        }
        let mut ends_driven = 0;
        for (field, member) in instances(l.field) {
            let doc = files.base(l, &field);
            let docs = [&doc, &files.design];
            let mut p = Probe {
                files: &files,
                limit: l,
                range: r,
                field: &field,
                failures: &mut failures,
            };
            let real = r.number == Number::Real;
            for (end, lo) in [(&r.lo, true), (&r.hi, false)] {
                let Some((e, closed, exact)) = end_value(end, docs, member) else {
                    if matches!(end, End::Unbounded) && real {
                        p.refused(if lo { f64::NEG_INFINITY } else { f64::INFINITY }, "∞");
                    }
                    continue;
                };
                ends_driven += 1;
                let outward = !lo;
                let step = |sign: f64| if outward { sign } else { -sign };
                let relative = 1e-9 * e.abs().max(1.0);
                let (beyond, inside) = match (real, closed, exact) {
                    (false, true, _) => (e + step(1.0), e),
                    (false, false, _) => (e, e - step(1.0)),
                    (true, true, true) => (next(e, outward), e),
                    (true, false, true) => (e, next(e, !outward)),
                    (true, true, false) => (e + step(relative), e - step(relative)),
                    (true, false, false) => (e, e - step(relative)),
                };
                let end = if lo { "the low end" } else { "the high end" };
                if let Some(said) = p.refused(beyond, &format!("beyond {end}")) {
                    p.not_refused(inside, &said, &format!("at or just inside {end}"));
                }
            }
            if real {
                p.refused(f64::NAN, "NaN");
            }
            if r.or_zero {
                p.not_refused(0.0, &l.text_of_refusal(), "0");
            }
            if let (Number::OddInteger, End::Num { value, .. }) = (r.number, r.lo) {
                p.refused(value + 1.0, "even");
            }
        }
        if ends_driven > 0 {
            driven += 1;
        } else {
            undriven.push(l.field);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(undriven, UNDRIVEN);
    let numeric = limits::all().filter(|l| l.range().is_some()).count();
    assert_eq!(driven + undriven.len(), numeric);
    assert!(
        driven >= 140 && files.loads.get() > 700,
        "{driven} numeric entries driven in {} loads",
        files.loads.get()
    );
    eprintln!(
        "{driven} numeric entries driven in {} loads; {} undriven",
        files.loads.get(),
        undriven.len()
    );
}
