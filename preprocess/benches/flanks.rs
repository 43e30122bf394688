//! `make bench`: flank grid generation (points/s) and UTCA time per position
//! on the white-paper pair, written as JSON (`bench/flanks.json`) and a table.
//! Target: UTCA over 2 mesh cycles at 0.1° in under 100 ms.

use geometry::design::Member;
use geometry::design_file::load_pair;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::UtcaSettings;
use geometry::utca::{roll_surface, sweep};
use preprocess::flank_stage::flank_grid;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

#[derive(Serialize)]
struct Entry {
    name: &'static str,
    value: f64,
    unit: &'static str,
    target: Option<f64>,
    note: String,
}

/// Median of `reps` timed runs, seconds.
fn time<T>(reps: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            std::hint::black_box(f());
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[reps / 2]
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let pair = load_pair(&root.join("reference/white_paper_20x43.toml")).expect("design");
    let s = UtcaSettings::default();
    let mut out = Vec::new();

    let t_geom = time(5, || PairGeometry::new(&pair).unwrap());
    out.push(Entry {
        name: "pair geometry (4 flanks, active regions)",
        value: t_geom * 1e3,
        unit: "ms",
        target: None,
        note: String::new(),
    });

    let g = PairGeometry::new(&pair).unwrap();
    let f = g.flank(Member::Pinion, Side::Drive);
    let (nf, np) = (s.flank_grid_face, s.flank_grid_profile);
    let t_grid = time(5, || flank_grid(f, nf, np).unwrap());
    out.push(Entry {
        name: "flank grid with curvatures",
        value: (nf * np) as f64 / t_grid,
        unit: "points/s",
        target: None,
        note: format!("{nf} x {np} grid in {:.1} ms", t_grid * 1e3),
    });
    let t_pts = time(5, || {
        let mut acc = 0.0;
        for i in 0..nf {
            for k in 0..np {
                acc += f
                    .at_unit(i as f64 / (nf - 1) as f64, k as f64 / (np - 1) as f64)
                    .unwrap()
                    .pos[0];
            }
        }
        acc
    });
    out.push(Entry {
        name: "flank points (position, normal) at (profile, face)",
        value: (nf * np) as f64 / t_pts,
        unit: "points/s",
        target: None,
        note: "cold Newton start per point".into(),
    });

    let fp = g.side(Side::Drive);
    let t_rs = time(5, || roll_surface(fp, &s).unwrap());
    let rs = roll_surface(fp, &s).unwrap();
    let t_sweep = time(5, || sweep(fp, &pair, &rs, &s));
    let n = sweep(fp, &pair, &rs, &s).te.len();
    out.push(Entry {
        name: "UTCA 2 mesh cycles at 0.1 deg (roll surface + sweep)",
        value: (t_rs + t_sweep) * 1e3,
        unit: "ms",
        target: Some(100.0),
        note: format!("{n} positions; roll surface {:.1} ms", t_rs * 1e3),
    });
    out.push(Entry {
        name: "UTCA per position",
        value: t_sweep * 1e6 / n as f64,
        unit: "us",
        target: None,
        note: String::new(),
    });

    // Flanks from machine settings: the synthesized settings of the same
    // design (no ease-off) against the designed pair, same run.
    let t_synth = time(5, || geometry::machine::synthesis::synthesize(&g).unwrap());
    out.push(Entry {
        name: "local synthesis (both pinion flanks)",
        value: t_synth * 1e3,
        unit: "ms",
        target: None,
        note: String::new(),
    });
    let mut cut = pair.clone();
    cut.ease_off = Default::default();
    cut.machine_settings = Some(
        geometry::machine::synthesis::synthesize(&g)
            .unwrap()
            .settings,
    );
    let t_cut = time(5, || PairGeometry::new(&cut).unwrap());
    out.push(Entry {
        name: "pair geometry from machine settings",
        value: t_cut * 1e3,
        unit: "ms",
        target: None,
        note: format!(
            "{:.1}x the designed pair's; the settings' deviation on 2 x 21 x 33 nodes per side",
            t_cut / t_geom
        ),
    });
    let gc = PairGeometry::new(&cut).unwrap();
    let fc = gc.side(Side::Drive);
    let rc = roll_surface(fc, &s).unwrap();
    let t_sweep_cut = time(5, || sweep(fc, &cut, &rc, &s));
    out.push(Entry {
        name: "UTCA per position, flanks from machine settings",
        value: t_sweep_cut * 1e6 / n as f64,
        unit: "us",
        target: None,
        note: format!(
            "{:.2}x the designed pair's (same run)",
            t_sweep_cut / t_sweep
        ),
    });

    let machine = format!(
        "{} cores, {}",
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        std::env::consts::ARCH
    );
    println!("\nflanks benchmark ({machine}, white-paper pair, median of 5)\n");
    println!(
        "{:<55} {:>14} {:>10} {:>8}  note",
        "what", "value", "unit", "target"
    );
    for e in &out {
        println!(
            "{:<55} {:>14.1} {:>10} {:>8}  {}",
            e.name,
            e.value,
            e.unit,
            e.target.map_or("-".into(), |t| format!("{t}")),
            e.note
        );
    }
    let dir = root.join("bench");
    std::fs::create_dir_all(&dir).unwrap();
    let json = serde_json::json!({ "machine": machine, "results": out });
    formats::output::write_json(&dir.join("flanks.json"), &json).unwrap();
    println!("\nwritten to bench/flanks.json");
}
