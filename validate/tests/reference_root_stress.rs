//! Root stress of the reference's bodies on example 03's coarse meshes
//! (the white-paper pair, 6 × 10 elements per flank): forces pressed into
//! the loaded flank of one tooth of the pinion, the fillets' stresses from
//! the reference's pruned backward solves on the fillets' support nodes
//! ([`Member::root_stress`]), against the same loads solved in full
//! (assembled, factored and solved over the whole body, stresses recovered
//! at every node by `fem::stress::nodal_stress`) — and the bending of the
//! loaded tooth: tension in the loaded flank's fillet, compression in the
//! other's.

#[path = "support/shared_meshes.rs"]
mod shared_meshes;

use fem::path_solve::combine;
use fem::{ClampedBody, Factorization};
use geometry::design::Member as Which;
use geometry::generation::Side;
use geometry::pair::{teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, Scene};
use preprocess::root_stress::{fillet_extremes, FilletStress};
use validate::reference::penalty::Term;
use validate::reference::reference_ltca::Member;

/// Outward unit normal of a flank face (its corners, oriented outward).
fn outward(nodes: &[[f64; 3]], f: &[usize; 6]) -> [f64; 3] {
    let [a, b, c] = [f[0], f[1], f[2]].map(|i| nodes[i]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / l)
}

#[test]
fn reference_root_stress_equals_the_full_solves_and_the_loaded_fillet_is_in_tension() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/03_reference_position/scene.toml");
    let scene = Scene::load(&dir).unwrap();
    let root = shared_meshes::reduced_meshes(&scene);
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let side = Side::Drive;
    let step = scene.scene.rotation.step_deg.to_radians();
    let teeth = teeth_in_contact(&g, side, 1.0, step).0;
    let path = formats::paths::msh(
        &root.join(&scene.scene.name),
        &formats::paths::stem_named(Which::Pinion, Blank::Standard, "reduced"),
    );
    let mut m = Member::load(&path, &g, Which::Pinion, side, &teeth, 64).unwrap();
    let fillets = m.root.as_ref().unwrap().fillets.clone();
    assert_eq!(fillets.len(), 2 * teeth.len(), "two fillets per tooth");
    for f in &fillets {
        eprintln!(
            "tooth {} {:?}: {} fillet nodes",
            f.tooth,
            f.side,
            f.nodes.len()
        );
        assert!(f.nodes.len() >= 10, "tooth {} {:?}", f.tooth, f.side);
        // The nodes found cover the fillet from toe to heel and from the
        // root to the flank junction (a wrong tooth turn finds none).
        let span = |v: &[f64]| {
            v.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                })
        };
        let (x0, x1) = span(&f.xi);
        let (h0, h1) = span(&f.height);
        assert!(
            x0 < 0.05 && x1 > 0.95 && h0 < 0.1 && h1 > 0.9,
            "tooth {} {:?}: xi {x0}..{x1}, height {h0}..{h1}",
            f.tooth,
            f.side
        );
    }

    // Three forces of 2 kN pressed into the middle tooth's loaded flank,
    // at face nodes spread over it.
    let tooth = teeth[teeth.len() / 2];
    let faces = m
        .mesh
        .group(&format!("tooth{tooth}_{}", side.flank_name(Which::Pinion)));
    let nodes = &m.mesh.mesh.nodes;
    let picks = [faces.len() / 4, faces.len() / 2, 3 * faces.len() / 4];
    let terms: Vec<Term> = picks
        .iter()
        .map(|&k| {
            let f = &faces[k];
            // The group's faces are oriented outward (the member orients
            // them); flip by the centroid test if not.
            let n = outward(nodes, f);
            Term {
                body: 0,
                node: f[0],
                dir: n.map(|c| -2000.0 * c),
            }
        })
        .collect();
    let loaded: Vec<usize> = terms.iter().map(|t| t.node).collect();
    m.compliance.ensure(&loaded).unwrap();
    let parts: Vec<_> = terms
        .iter()
        .map(|t| {
            m.compliance
                .constraint_vector(std::slice::from_ref(t), 0)
                .unwrap()
        })
        .collect();
    let one = [1.0];
    let z = combine(&parts.iter().map(|p| (p, &one[..])).collect::<Vec<_>>());
    let pruned = m.root_stress(&[&z], &teeth).unwrap().remove(0);

    // The same loads solved in full.
    let material = preprocess::influence::fe_material(g.data.member(Which::Pinion).material());
    let bore = m.mesh.group_nodes("bore");
    let body = ClampedBody::new(
        &m.mesh.mesh,
        &material,
        &fem::clamp_nodes(&bore),
        Factorization::Auto,
    )
    .unwrap();
    let mut f = vec![0.0; body.dofs.n_free()];
    for t in &terms {
        for c in 0..3 {
            if let Some(d) = body.dofs.free_index(3 * t.node + c) {
                f[d] += t.dir[c];
            }
        }
    }
    let u = body.dofs.expand(&body.factor.solve(&f));
    let s = fem::stress::nodal_stress(&m.mesh.mesh, &material, &u);
    let full: Vec<FilletStress> = fillets
        .iter()
        .map(|fl| {
            let at: Vec<_> = fl.nodes.iter().map(|&n| s[n]).collect();
            fillet_extremes(fl, &at)
        })
        .collect();
    let scale = full
        .iter()
        .map(|r| r.max_principal_pa.abs().max(r.min_principal_pa.abs()))
        .fold(0.0, f64::max);
    for (a, b) in pruned.iter().zip(&full) {
        eprintln!(
            "tooth {} loaded side {}: sigma1 max {:.3} MPa at xi {:.2} h {:.2}; sigma3 min {:.3} MPa",
            a.tooth,
            a.loaded_side,
            a.max_principal_pa * 1e-6,
            a.max_xi,
            a.max_height,
            a.min_principal_pa * 1e-6
        );
        assert!(
            (a.max_principal_pa - b.max_principal_pa).abs() <= 1e-9 * scale
                && (a.min_principal_pa - b.min_principal_pa).abs() <= 1e-9 * scale,
            "pruned {a:?} against full {b:?}"
        );
        assert_eq!((a.max_xi, a.max_height), (b.max_xi, b.max_height));
    }

    // The loaded tooth bends away from its loaded flank: its largest
    // tension lies in that flank's fillet, its largest compression in the
    // other's, and both stand above what the neighbouring teeth see.
    let of = |t: usize, loaded: bool| {
        *pruned
            .iter()
            .find(|r| r.tooth == t && r.loaded_side == loaded)
            .unwrap()
    };
    let (l, o) = (of(tooth, true), of(tooth, false));
    assert!(
        l.max_principal_pa > 0.0 && l.max_principal_pa > o.max_principal_pa,
        "tension: loaded {l:?}, opposite {o:?}"
    );
    assert!(
        o.min_principal_pa < 0.0 && o.min_principal_pa < l.min_principal_pa,
        "compression: loaded {l:?}, opposite {o:?}"
    );
    for r in pruned.iter().filter(|r| r.tooth != tooth) {
        assert!(
            r.max_principal_pa < l.max_principal_pa,
            "neighbour {r:?} above the loaded tooth {l:?}"
        );
    }
}
