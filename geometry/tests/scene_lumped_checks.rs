//! `[lumped]` scene section: defaults pass the checks, every out-of-range
//! value is refused with the field, the value and the limit named, and an
//! unknown key is refused.

use geometry::scene_lumped::{ImpactModel, LumpedSettings};
use std::path::Path;

#[test]
fn scene_lumped_checks_name_field_value_and_limit() {
    let p = Path::new("scene.toml");
    LumpedSettings::default().check(p).unwrap();
    type Edit = fn(&mut LumpedSettings);
    let cases: [(Edit, &str, &str); 6] = [
        (
            |s| s.pinion_speed_rpm = -1.0,
            "lumped.pinion_speed_rpm",
            "-1",
        ),
        (
            |s| s.dropped_mesh_cycles = 50.0,
            "lumped.dropped_mesh_cycles",
            "50",
        ),
        (
            |s| s.samples_per_mesh_cycle = 4,
            "lumped.samples_per_mesh_cycle",
            "4",
        ),
        (
            |s| s.mesh_damping_ratio = f64::NAN,
            "lumped.mesh_damping_ratio",
            "NaN",
        ),
        (
            |s| s.wheel_bearing_stiffness_n_per_m[1] = 0.0,
            "lumped.wheel_bearing_stiffness_n_per_m",
            "0.0",
        ),
        (
            |s| s.pinion_mass_kg = Some(0.0),
            "lumped.pinion_mass_kg",
            "0",
        ),
    ];
    for (edit, field, value) in cases {
        let mut s = LumpedSettings::default();
        edit(&mut s);
        let e = s.check(p).expect_err(field).to_string();
        assert!(e.contains(field) && e.contains(value), "{e}");
    }
}

#[test]
fn scene_lumped_section_parses_and_refuses_unknown_keys() {
    let s: LumpedSettings =
        toml::from_str("pinion_speed_rpm = 5900.0\nimpact = \"seed004\"\n").unwrap();
    assert_eq!(s.pinion_speed_rpm, 5900.0);
    assert_eq!(s.impact, ImpactModel::Seed004);
    assert_eq!(s.mesh_cycles, LumpedSettings::default().mesh_cycles);
    assert!(toml::from_str::<LumpedSettings>("pinion_speed = 1.0\n").is_err());
}
