//! The flank stage's key numbers as golden quantities, shared by the
//! numbered examples that run it (01: the designed pair, 04: the pair cut
//! by machine settings).

#![allow(dead_code)]

use crate::golden::Quantity;
use preprocess::flank_stage::FlankSummary;
use serde_json::Value;

/// Relative tolerance of every value.
pub const REL: f64 = 1e-9;

pub fn read(path: &std::path::Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

pub fn num(v: &Value, what: &str) -> f64 {
    v.as_f64()
        .unwrap_or_else(|| panic!("{what}: not a number: {v}"))
}

/// summary.json's key numbers into `q` (`s`; `summary` the returned
/// FlankSummary).
pub fn summary_quantities(q: &mut Vec<Quantity>, s: &Value, summary: &FlankSummary) {
    q.push(Quantity::new(
        "mesh_cycle_deg",
        summary.mesh_cycle_deg,
        "deg",
        REL,
        0.0,
    ));
    q.push(Quantity::new(
        "crown_gear_teeth",
        summary.crown_gear_teeth,
        "",
        REL,
        0.0,
    ));
    q.push(Quantity::new(
        "normal_backlash_mm",
        summary.normal_backlash_mm,
        "mm",
        REL,
        1e-12,
    ));
    q.push(Quantity::new(
        "mean_normal_thickness_mm.pinion",
        summary.mean_normal_thickness_mm[0],
        "mm",
        REL,
        0.0,
    ));
    q.push(Quantity::new(
        "mean_normal_thickness_mm.wheel",
        summary.mean_normal_thickness_mm[1],
        "mm",
        REL,
        0.0,
    ));
    for (m, f) in [("pinion", "concave"), ("pinion", "convex")] {
        let mp = &s["mean_point"][m][f];
        q.push(Quantity::new(
            format!("mean_point.{m}.{f}.spiral_angle_deg"),
            num(&mp["spiral_angle_deg"], "spiral angle"),
            "deg",
            REL,
            1e-9,
        ));
        q.push(Quantity::new(
            format!("mean_point.{m}.{f}.normal_pressure_angle_deg"),
            num(&mp["normal_pressure_angle_deg"], "pressure angle"),
            "deg",
            REL,
            1e-9,
        ));
    }
    q.push(Quantity::new(
        "utca.te_ptp_urad",
        summary.utca.te_ptp_urad,
        "urad",
        REL,
        1e-9,
    ));
    q.push(Quantity::new(
        "utca.te_mean_urad",
        summary.utca.te_mean_urad,
        "urad",
        REL,
        1e-9,
    ));
    q.push(Quantity::new(
        "utca.contact_ratio",
        summary.utca.contact_ratio,
        "",
        REL,
        0.0,
    ));
    q.push(Quantity::new(
        "utca.positions",
        summary.utca.positions as f64,
        "",
        0.0,
        0.0,
    ));
}

/// Into `q`: utca.json's roll range, the TE at five positions, and the contact path
/// at the middle of the sweep.
pub fn utca_quantities(q: &mut Vec<Quantity>, u: &Value) {
    for (k, v) in u["roll_range_deg"].as_array().unwrap().iter().enumerate() {
        q.push(Quantity::new(
            format!("utca.roll_range_deg[{k}]"),
            num(v, "roll range"),
            "deg",
            REL,
            1e-9,
        ));
    }
    let te = u["te_urad"].as_array().unwrap();
    for k in [
        0,
        te.len() / 4,
        te.len() / 2,
        3 * te.len() / 4,
        te.len() - 1,
    ] {
        q.push(Quantity::new(
            format!("utca.pinion_rotation_deg[{k}]"),
            num(&u["pinion_rotation_deg"][k], "rotation"),
            "deg",
            REL,
            1e-9,
        ));
        q.push(Quantity::new(
            format!("utca.te_urad[{k}]"),
            num(&te[k], "te"),
            "urad",
            REL,
            1e-9,
        ));
    }
    let path = u["path"].as_array().unwrap();
    let p = &path[path.len() / 2];
    let at = format!("utca.path[{}]", path.len() / 2);
    q.push(Quantity::new(
        format!("{at}.tooth"),
        num(&p["tooth"], "tooth"),
        "",
        0.0,
        0.0,
    ));
    q.push(Quantity::new(
        format!("{at}.cone_distance_mm"),
        num(&p["cone_distance_mm"], "L"),
        "mm",
        REL,
        1e-12,
    ));
    q.push(Quantity::new(
        format!("{at}.height_mm"),
        num(&p["height_mm"], "d"),
        "mm",
        REL,
        1e-12,
    ));
    q.push(Quantity::new(
        format!("{at}.ellipse_major_semi_axis_mm"),
        num(&p["ellipse_semi_axes_mm"][0], "a"),
        "mm",
        REL,
        1e-12,
    ));
    q.push(Quantity::new(
        format!("{at}.ellipse_minor_semi_axis_mm"),
        num(&p["ellipse_semi_axes_mm"][1], "b"),
        "mm",
        REL,
        1e-12,
    ));
}

/// Into `q`: flanks.json's three grid points of the loaded pinion flank (toe-root,
/// middle, heel-tip corner) and the middle of the wheel's loaded flank.
pub fn flank_quantities(q: &mut Vec<Quantity>, grids: &Value) {
    for g in grids.as_array().unwrap() {
        let (member, flank, side) = (
            g["member"].as_str().unwrap(),
            g["flank"].as_str().unwrap(),
            g["side"].as_str().unwrap(),
        );
        if side != "drive" {
            continue;
        }
        let (nf, np) = (
            g["n_face"].as_u64().unwrap() as usize,
            g["n_profile"].as_u64().unwrap() as usize,
        );
        let nodes: Vec<(usize, usize)> = if member == "pinion" {
            vec![(0, 0), (nf / 2, np / 2), (nf - 1, np - 1)]
        } else {
            vec![(nf / 2, np / 2)]
        };
        for (i, k) in nodes {
            let n = i * np + k;
            let at = format!("flanks.{member}.{flank}[face {i}, profile {k}]");
            for (c, axis) in ["x", "y", "z"].iter().enumerate() {
                q.push(Quantity::new(
                    format!("{at}.position_m.{axis}"),
                    num(&g["position_m"][n][c], "position"),
                    "m",
                    REL,
                    1e-12,
                ));
            }
            if member == "pinion" {
                q.push(Quantity::new(
                    format!("{at}.pinion_roll_deg"),
                    num(&g["pinion_roll_deg"][n], "roll"),
                    "deg",
                    REL,
                    1e-9,
                ));
                q.push(Quantity::new(
                    format!("{at}.ease_off_um"),
                    num(&g["ease_off_um"][n], "ease-off"),
                    "um",
                    REL,
                    1e-9,
                ));
            }
        }
    }
}
