//! The multibody contact table of a lightweight pair starts a lead-in
//! before the sweep (the rotation over which the first position's loaded
//! lag builds up), longer with the torque and the table step. The
//! stiffness plan solves the teeth of that lead-in, bounded a priori
//! ([`geometry::teeth::table_span`]): the bound holds a table built on the
//! example-02 fixture (its actual lead-in), and the planned teeth cover
//! every tooth the table's span meets, at the coarsest allowed table step
//! and a high torque (which needs a wheel tooth the sweep alone does not).

#[path = "support/fixture.rs"]
mod fixture;

use geometry::design::Member;
use geometry::pair::{pairs_in_contact, pinion_direction, PairGeometry};
use geometry::scene::{Blank, Scene};
use geometry::teeth::{refined_teeth, table_positions_per_cycle, table_span, table_torque_nm};
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use std::collections::BTreeSet;
use std::path::Path;

#[test]
fn the_planned_lead_in_bounds_the_lead_in_of_a_table_built_on_the_fixture() {
    let f = fixture::Fixture::example_02();
    let d = &f.g.data;
    let ratio = d.members[0].teeth as f64 / d.members[1].teeth as f64;
    let tau = d.mesh_cycle();
    let sc = &f.scene.scene;
    // The fixture's torques (100, 300 N·m) times the table factor, and a
    // ten times larger load.
    for scale in [1.0, 10.0] {
        let torque = table_torque_nm(sc, Blank::Standard, ratio) * scale;
        let per = table_positions_per_cycle(sc, tau);
        let spec = TableSpec {
            start: f.sweep.start,
            direction: f.sweep.direction,
            step: tau / per as f64,
            positions: per + 3,
            periodic: false,
            slices: sc.ltca.slices,
            lag_nodes: 24,
            torque_max_nm: torque,
        };
        let table = MeshTable::build(f.fp(), &f.rs, &f.pc, &f.g.frames[0], ratio, spec).unwrap();
        let lead = table.lead as f64 * table.spec.step;
        let mut scaled = sc.clone();
        scaled.pinion_torque_nm = sc.pinion_torque_nm.iter().map(|t| t * scale).collect();
        let bound = table_span(&f.g, &scaled, Blank::Standard, f.sweep.step)[0];
        println!(
            "table torque {torque} N m: lead-in {:.3} deg, planned {:.3} deg",
            lead.to_degrees(),
            bound.to_degrees()
        );
        assert!(
            table.lead > 2,
            "the lead-in is more than its two margin steps"
        );
        assert!(
            lead <= bound,
            "lead-in {lead} rad beyond the plan's {bound}"
        );
    }
}

/// Wheel teeth touching at the pinion angles of `ks` table steps from the
/// sweep's start.
fn teeth_at(
    g: &PairGeometry,
    sc: &Scene,
    ks: std::ops::RangeInclusive<i64>,
    step: f64,
) -> BTreeSet<usize> {
    let fp = g.side(sc.loaded_flank);
    let dir = pinion_direction(&g.data, sc.loaded_flank);
    let z2 = g.data.members[1].teeth as i64;
    ks.flat_map(|k| {
        pairs_in_contact(
            fp.roll_range[0] + dir * step * k as f64,
            fp.roll_range,
            g.data.mesh_cycle(),
        )
    })
    .map(|j| (-(j as i64)).rem_euclid(z2) as usize)
    .collect()
}

#[test]
fn planned_teeth_cover_the_table_span_at_a_coarse_step_and_a_high_torque() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference");
    let text = std::fs::read_to_string(root.join("scenes/default.toml"))
        .unwrap()
        .replace(
            "design = \"../white_paper_20x43.toml\"",
            &format!("design = {:?}", root.join("white_paper_20x43.toml")),
        )
        .replace(
            "pinion_torque_nm = [1.0, 100.0, 300.0, 500.0, 700.0]",
            "pinion_torque_nm = [100.0, 700.0, 5000.0]",
        )
        + "\n[multibody]\ntable_step_deg = 2.0\n";
    let tmp = tempfile_path();
    std::fs::write(&tmp, text).unwrap();
    let scene = Scene::load(&tmp).unwrap();
    let _ = std::fs::remove_file(&tmp);
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let tau = g.data.mesh_cycle();
    let step = sc.rotation.step_deg.to_radians();
    let [before, after] = table_span(&g, sc, Blank::Lightweight, step);
    let table_step = tau / table_positions_per_cycle(sc, tau) as f64;
    let ks = -(before / table_step).ceil() as i64..=(after / table_step).ceil() as i64;
    let met = teeth_at(&g, sc, ks, table_step);
    let planned: BTreeSet<usize> = refined_teeth(&g, sc, Member::Wheel, Blank::Lightweight)
        .into_iter()
        .collect();
    assert!(
        met.is_subset(&planned),
        "the table meets {met:?}, the plan solves {planned:?}"
    );
    // The case is the one the plan used to miss: the lead-in meets a tooth
    // the sweep and the run-up alone do not.
    let n = (sc.contact_mesh_cycles(Blank::Lightweight, tau) * tau / step).round() as i64;
    let sweep_only = teeth_at(&g, sc, 0..=n, step);
    assert!(
        !met.is_subset(&sweep_only),
        "the lead-in adds no tooth: {met:?}"
    );
}

fn tempfile_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("table_lead_in_{}.toml", std::process::id()))
}
