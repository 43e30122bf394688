//! The flank fidelity check of the mesh tests (`mesh.rs`, `mesh_levels.rs`):
//! every flank-group node of a pinion mesh on the generated flank.

use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use preprocess::mesh::MeshReport;

/// Flank fidelity: every node of a flank group within 0.5 µm of
/// the generated flank along its normal.
pub const FLANK_TOLERANCE: f64 = 0.5e-6;

/// Checks that every flank-group node of the pinion mesh at `path` lies on
/// the generated flank within [`FLANK_TOLERANCE`] and that the report agrees
/// (nothing left unsnapped, valid tets).
pub fn assert_flank_nodes_on_the_generated_flank(
    g: &PairGeometry,
    report: &MeshReport,
    path: &std::path::Path,
) {
    let refined: Vec<String> = report
        .refined_flanks
        .iter()
        .map(|r| format!("tooth{}_{}", r.tooth, r.flank))
        .collect();
    assert!(!refined.is_empty());
    let s = gmsh::Session::new().unwrap();
    s.open(path).unwrap();
    let pitch = 2.0 * std::f64::consts::PI / g.data.member(Member::Pinion).teeth as f64;
    // (normal distance, on a refined flank), every flank-group node once.
    let mut seen = std::collections::BTreeSet::new();
    let mut all = Vec::new();
    for (dim, tag) in s.get_physical_groups(2).unwrap() {
        let name = s.get_physical_name(dim, tag).unwrap();
        let Some(rest) = name.strip_prefix("tooth") else {
            continue;
        };
        let (k, flank) = rest.split_once('_').unwrap();
        let k: usize = k.parse().unwrap();
        let side = if flank == "concave" {
            Side::Drive
        } else {
            Side::Coast
        };
        let f = g.flank(Member::Pinion, side);
        for e in s.get_entities_for_physical_group(dim, tag).unwrap() {
            let (tags, xyz, _) = s.mesh_get_nodes(2, e, true, false).unwrap();
            for (t, p) in tags.iter().zip(xyz.chunks(3)) {
                if !seen.insert(*t) {
                    continue;
                }
                let a = -(k as f64) * pitch;
                let (sa, ca) = a.sin_cos();
                let q = [ca * p[0] - sa * p[1], sa * p[0] + ca * p[1], p[2]];
                let (l, d) = f.gen.frame.axial(&q);
                let fp = f.at(l, d).unwrap();
                let dist: f64 = (0..3).map(|i| (q[i] - fp.pos[i]) * fp.normal[i]).sum();
                all.push((dist.abs(), refined.contains(&name)));
            }
        }
    }
    let worst = |on_refined: bool| {
        all.iter()
            .filter(|a| a.1 == on_refined)
            .map(|a| a.0)
            .fold(0.0, f64::max)
    };
    let over = all.iter().filter(|a| a.0 > FLANK_TOLERANCE).count();
    println!(
        "{} level: {} flank nodes ({} refined), largest normal distance {:.4} um refined, {:.4} um other; {over} over 0.5 um; report: {} snapped (largest move {:.3} um), {} kept, {} flank caps and {} other caps removed, {} interior nodes carried, min SICN {:.2e}",
        report.level,
        all.len(),
        all.iter().filter(|a| a.1).count(),
        worst(true) * 1e6,
        worst(false) * 1e6,
        report.snapped_nodes,
        report.snap_max_move_um,
        report.unsnapped_nodes,
        report.caps_removed,
        report.other_caps_removed,
        report.carried_nodes,
        report.quality_min_sicn
    );
    assert!(all.iter().filter(|a| a.1).count() > 1000);
    assert!(
        worst(true) < FLANK_TOLERANCE,
        "refined flank node {:.3} um off the generated flank",
        worst(true) * 1e6
    );
    // Every flank-group face is a flank: no sliver of the top land or heel
    // (which would sit a millimetre or more off) was put into a flank group.
    assert!(
        worst(false) < 0.5e-3,
        "a flank-group node {:.3} mm off the generated flank",
        worst(false) * 1e3
    );
    // Every other flank node too: caps were removed and slivers carried,
    // not left off the flank.
    assert_eq!(over, 0, "{over} flank nodes over 0.5 um");
    assert_eq!(report.unsnapped_nodes, 0);
    assert!(
        report.quality_min_sicn >= 1e-4,
        "min SICN {} after snapping",
        report.quality_min_sicn
    );
    // Without snapping the loft is off by about 0.5 µm at the median: the
    // snap must have moved the flank nodes.
    assert!(report.snapped_nodes + report.unsnapped_nodes >= all.len());
    assert!(report.snap_max_move_um > 0.5);
}
