//! `[lumped]` scene section: defaults pass the checks, every out-of-range
//! value is refused with the field, the value and the limit named, and an
//! unknown key is refused.

use geometry::scene_lumped::{
    DirectionSource, ImpactModel, LumpedFriction, LumpedRoughness, LumpedSettings, OrderMapSettings,
};
use std::path::Path;

#[test]
fn scene_lumped_checks_name_field_value_and_limit() {
    let p = Path::new("scene.toml");
    LumpedSettings::default().check(p).unwrap();
    type Edit = fn(&mut LumpedSettings);
    let cases: [(Edit, &str, &str); 10] = [
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
        (
            |s| s.more_pinion_torques_nm = vec![10.0, -5.0],
            "lumped.more_pinion_torques_nm",
            "-5",
        ),
        (
            |s| {
                s.friction = Some(LumpedFriction {
                    base_coefficient: 2.5,
                    roughness_coefficient_per_um: 0.01,
                })
            },
            "lumped.friction.base_coefficient",
            "2.5",
        ),
        (
            |s| {
                s.roughness = Some(LumpedRoughness {
                    ra_um: vec![0.8, 0.0],
                    seed: 3,
                    profile_nodes: 41,
                    face_nodes: 5,
                })
            },
            "lumped.roughness.ra_um",
            "0",
        ),
        (
            |s| {
                s.roughness = Some(LumpedRoughness {
                    ra_um: vec![0.8],
                    seed: 3,
                    profile_nodes: 201,
                    face_nodes: 5,
                })
            },
            "lumped.roughness.profile_nodes",
            "201",
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
    let s: LumpedSettings = toml::from_str(
        "direction_cosines = \"ltca\"\nmore_pinion_torques_nm = [62.22]\n[friction]\nbase_coefficient = 0.6\nroughness_coefficient_per_um = 0.01\n[roughness]\nra_um = [0.8]\nseed = 3\nprofile_nodes = 41\nface_nodes = 5\n",
    )
    .unwrap();
    assert_eq!(s.direction_cosines, DirectionSource::Ltca);
    assert_eq!(s.roughness.unwrap().ra_um, vec![0.8]);
    assert!(
        toml::from_str::<LumpedSettings>("[friction]\nbase_coefficient = 0.6\nmu_r = 0.01\n")
            .is_err()
    );
}

/// A valid `[order_map]` table, one line per field.
const ORDER_MAP: [&str; 4] = [
    "pinion_speeds_rpm = [1000.0, 3000.0]",
    "wheel_revolutions = 3.0",
    "dropped_wheel_revolutions = 1.0",
    "max_pinion_order = 50.0",
];

/// `[order_map]` with line `line` replaced by `with` (None: as it is).
fn order_map_toml(line: usize, with: Option<&str>) -> String {
    let mut t = String::from("[order_map]\n");
    for (i, l) in ORDER_MAP.iter().enumerate() {
        t.push_str(if i == line { with.unwrap_or(l) } else { l });
        t.push('\n');
    }
    t
}

#[test]
fn scene_lumped_order_map_refuses_no_speed_a_bad_speed_and_no_kept_revolution() {
    let p = Path::new("scene.toml");
    let ok: LumpedSettings = toml::from_str(&order_map_toml(0, None)).unwrap();
    ok.check(p).unwrap();
    let o: &OrderMapSettings = ok.order_map.as_ref().unwrap();
    assert_eq!(o.pinion_speeds_rpm, vec![1000.0, 3000.0]);
    let refused = [
        (
            0,
            "pinion_speeds_rpm = []",
            "pinion_speeds_rpm",
            "0 entries",
        ),
        (
            0,
            "pinion_speeds_rpm = [1000.0, -5.0]",
            "pinion_speeds_rpm",
            "-5",
        ),
        (1, "wheel_revolutions = 0.5", "wheel_revolutions", "0.5"),
        (
            2,
            "dropped_wheel_revolutions = 2.5",
            "dropped_wheel_revolutions",
            "2.5",
        ),
        (3, "max_pinion_order = inf", "max_pinion_order", "inf"),
    ];
    for (line, with, field, value) in refused {
        let s: LumpedSettings = toml::from_str(&order_map_toml(line, Some(with))).unwrap();
        let e = s.check(p).expect_err(field).to_string();
        assert!(
            e.contains(&format!("lumped.order_map.{field}")) && e.contains(value),
            "{e}"
        );
    }
    let unknown = order_map_toml(3, Some("max_pinion_order = 50.0\nlobes = 3"));
    assert!(toml::from_str::<LumpedSettings>(&unknown).is_err());
}
