//! Tests against the real gmsh library (no mocks). Every test creates its own
//! `Session`; the test harness runs them on parallel threads, so they also
//! exercise the process-wide session lock.

use std::f64::consts::PI;

use gmsh::{GmshError, Session};

fn session() -> Session {
    Session::new().expect("gmsh session")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A closed rectangle in the plane y = 0: `[x0, x1] x [z0, z1]`, as a plane
/// surface; returns its tag.
fn rectangle_xz(g: &Session, x0: f64, x1: f64, z0: f64, z1: f64) -> i32 {
    let p = [
        g.occ_add_point(x0, 0.0, z0, 0.0, -1).unwrap(),
        g.occ_add_point(x1, 0.0, z0, 0.0, -1).unwrap(),
        g.occ_add_point(x1, 0.0, z1, 0.0, -1).unwrap(),
        g.occ_add_point(x0, 0.0, z1, 0.0, -1).unwrap(),
    ];
    let l: Vec<i32> = (0..4)
        .map(|i| g.occ_add_line(p[i], p[(i + 1) % 4]).unwrap())
        .collect();
    let cl = g.occ_add_curve_loop(&l).unwrap();
    g.occ_add_plane_surface(&[cl]).unwrap()
}

/// A full circle of radius `r` around the z axis at height `z`, as a wire
/// made of two arcs; returns the wire tag.
fn circle_wire(g: &Session, r: f64, z: f64) -> i32 {
    let c = g.occ_add_point(0.0, 0.0, z, 0.0, -1).unwrap();
    let a = g.occ_add_point(r, 0.0, z, 0.0, -1).unwrap();
    let b = g.occ_add_point(-r, 0.0, z, 0.0, -1).unwrap();
    // Two half circles (a single arc cannot span 180 degrees unambiguously).
    let top = g.occ_add_point(0.0, r, z, 0.0, -1).unwrap();
    let bottom = g.occ_add_point(0.0, -r, z, 0.0, -1).unwrap();
    let arcs = [
        g.occ_add_circle_arc(a, c, top).unwrap(),
        g.occ_add_circle_arc(top, c, b).unwrap(),
        g.occ_add_circle_arc(b, c, bottom).unwrap(),
        g.occ_add_circle_arc(bottom, c, a).unwrap(),
    ];
    g.occ_add_wire(&arcs, true).unwrap()
}

#[test]
fn version_check_passes() {
    let g = session();
    assert_eq!(g.version().unwrap(), gmsh_sys::BINDINGS_GMSH_VERSION);
    assert_eq!(gmsh::GMSH_VERSION, "4.15.2");
    // Terminal output is off unless GMSH_VERBOSE is set.
    if std::env::var_os("GMSH_VERBOSE").is_none() {
        assert_eq!(g.option_get_number("General.Terminal").unwrap(), 0.0);
    }
}

#[test]
fn box_mass_and_center() {
    let g = session();
    g.add_model("box").unwrap();
    let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 2.0, 3.0).unwrap();
    g.occ_synchronize().unwrap();
    assert!((g.occ_get_mass(3, v).unwrap() - 6.0).abs() < 1e-12);
    let c = g.occ_get_center_of_mass(3, v).unwrap();
    for (a, b) in c.iter().zip([0.5, 1.0, 1.5]) {
        assert!((a - b).abs() < 1e-12, "{c:?}");
    }
    let bb = g.get_bounding_box(3, v).unwrap();
    for (a, b) in bb.iter().zip([0.0, 0.0, 0.0, 1.0, 2.0, 3.0]) {
        assert!((a - b).abs() < 1e-6, "{bb:?}");
    }
    assert_eq!(g.get_entities(3).unwrap(), vec![(3, v)]);
    assert_eq!(g.get_entities(2).unwrap().len(), 6);
    assert_eq!(g.occ_get_entities(1).unwrap().len(), 12);
    let faces = g.get_boundary(&[(3, v)], false, false, false).unwrap();
    assert_eq!(faces.len(), 6);
    let points = g.get_boundary(&[(3, v)], false, false, true).unwrap();
    assert_eq!(points.len(), 8);
    assert!(points.iter().all(|&(d, _)| d == 0));
    let (up, down) = g.get_adjacencies(2, faces[0].1).unwrap();
    assert_eq!(up, vec![v]);
    assert_eq!(down.len(), 4);
    assert_eq!(g.get_type(3, v).unwrap(), "Volume");
    assert_eq!(g.get_type(2, faces[0].1).unwrap(), "Plane");
}

#[test]
fn cylinder_volume() {
    let g = session();
    let (r, h) = (0.7, 2.5);
    let v = g.occ_add_cylinder(1.0, -2.0, 0.5, 0.0, 0.0, h, r).unwrap();
    g.occ_synchronize().unwrap();
    let vol = g.occ_get_mass(3, v).unwrap();
    assert!((vol - PI * r * r * h).abs() < 1e-9, "{vol}");
    let cone = g
        .occ_add_cone(0.0, 0.0, 10.0, 0.0, 0.0, h, r, 0.5 * r)
        .unwrap();
    g.occ_synchronize().unwrap();
    let exact = PI * h / 3.0 * (r * r + r * 0.5 * r + 0.25 * r * r);
    assert!(rel(g.occ_get_mass(3, cone).unwrap(), exact) < 1e-9);
}

#[test]
fn revolve_rectangle_gives_pappus_annulus() {
    let g = session();
    let (r0, r1, z0, z1) = (2.0, 3.0, -0.5, 1.5);
    let s = rectangle_xz(&g, r0, r1, z0, z1);
    g.occ_synchronize().unwrap();
    let area = g.occ_get_mass(2, s).unwrap();
    assert!((area - (r1 - r0) * (z1 - z0)).abs() < 1e-12);
    let out = g
        .occ_revolve(&[(2, s)], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0 * PI)
        .unwrap();
    g.occ_synchronize().unwrap();
    let vols: Vec<i32> = out
        .iter()
        .filter(|&&(d, _)| d == 3)
        .map(|&(_, t)| t)
        .collect();
    assert_eq!(vols.len(), 1, "{out:?}");
    let vol = g.occ_get_mass(3, vols[0]).unwrap();
    // Pappus: area times the path length of the centroid.
    let pappus = (r1 - r0) * (z1 - z0) * 2.0 * PI * 0.5 * (r0 + r1);
    assert!((vol - pappus).abs() < 1e-9, "{vol} vs {pappus}");
    assert!((vol - PI * (r1 * r1 - r0 * r0) * (z1 - z0)).abs() < 1e-9);
}

#[test]
fn thru_sections_two_circles_is_a_frustum() {
    let g = session();
    let (r1, r2, h) = (2.0, 1.0, 3.0);
    let w1 = circle_wire(&g, r1, 0.0);
    let w2 = circle_wire(&g, r2, h);
    let out = g
        .occ_add_thru_sections(&[w1, w2], true, false, -1, "", "", false)
        .unwrap();
    g.occ_synchronize().unwrap();
    let vols: Vec<i32> = out
        .iter()
        .filter(|&&(d, _)| d == 3)
        .map(|&(_, t)| t)
        .collect();
    assert_eq!(vols.len(), 1, "{out:?}");
    let vol = g.occ_get_mass(3, vols[0]).unwrap();
    let frustum = PI * h / 3.0 * (r1 * r1 + r1 * r2 + r2 * r2);
    assert!(rel(vol, frustum) < 1e-6, "{vol} vs {frustum}");
}

#[test]
fn cut_cylinder_from_box() {
    let g = session();
    let b = g.occ_add_box(0.0, 0.0, 0.0, 4.0, 4.0, 2.0).unwrap();
    let (r, h) = (1.0, 2.0);
    let c = g.occ_add_cylinder(2.0, 2.0, 0.0, 0.0, 0.0, h, r).unwrap();
    let (out, map) = g.occ_cut(&[(3, b)], &[(3, c)], true, true).unwrap();
    g.occ_synchronize().unwrap();
    assert_eq!(out.len(), 1, "{out:?}");
    assert_eq!(map.len(), 2, "{map:?}");
    assert_eq!(map[0], out);
    assert!(map[1].is_empty(), "{map:?}");
    let vol = g.occ_get_mass(3, out[0].1).unwrap();
    assert!((vol - (32.0 - PI * r * r * h)).abs() < 1e-9, "{vol}");
    assert_eq!(g.get_entities(3).unwrap(), out);
}

#[test]
fn fuse_intersect_fragment_copy_remove() {
    let g = session();
    let a = g.occ_add_box(0.0, 0.0, 0.0, 2.0, 1.0, 1.0).unwrap();
    let b = g.occ_add_box(1.0, 0.0, 0.0, 2.0, 1.0, 1.0).unwrap();
    let a2 = g.occ_copy(&[(3, a)]).unwrap();
    let b2 = g.occ_copy(&[(3, b)]).unwrap();
    let a3 = g.occ_copy(&[(3, a)]).unwrap();
    let b3 = g.occ_copy(&[(3, b)]).unwrap();
    let (fused, _) = g.occ_fuse(&[(3, a)], &[(3, b)], true, true).unwrap();
    let (common, _) = g.occ_intersect(&a2, &b2, true, true).unwrap();
    g.occ_synchronize().unwrap();
    assert_eq!(fused.len(), 1);
    assert!((g.occ_get_mass(3, fused[0].1).unwrap() - 3.0).abs() < 1e-9);
    assert!((g.occ_get_mass(3, common[0].1).unwrap() - 1.0).abs() < 1e-9);
    g.occ_remove(&fused, true).unwrap();
    g.occ_remove(&common, true).unwrap();
    let (pieces, map) = g.occ_fragment(&a3, &b3, true, true).unwrap();
    g.occ_synchronize().unwrap();
    assert_eq!(pieces.len(), 3, "{pieces:?}");
    assert_eq!(map.len(), 2);
    assert_eq!(map[0].len(), 2);
    assert_eq!(map[1].len(), 2);
    let total: f64 = pieces
        .iter()
        .map(|&(d, t)| g.occ_get_mass(d, t).unwrap())
        .sum();
    assert!((total - 3.0).abs() < 1e-9);
    assert_eq!(g.get_entities(3).unwrap().len(), 3);
}

#[test]
fn extrude_rotate_heal_and_curves() {
    let g = session();
    let s = rectangle_xz(&g, 0.0, 1.0, 0.0, 2.0);
    let out = g.occ_extrude(&[(2, s)], 0.0, 3.0, 0.0).unwrap();
    assert_eq!(out[1].0, 3, "{out:?}");
    g.occ_rotate(&out[1..2], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.5 * PI)
        .unwrap();
    let healed = g.occ_heal_shapes(&[]).unwrap();
    assert!(!healed.is_empty());
    g.occ_synchronize().unwrap();
    let vols = g.get_entities(3).unwrap();
    assert_eq!(vols.len(), 1);
    assert!((g.occ_get_mass(3, vols[0].1).unwrap() - 6.0).abs() < 1e-9);
    // Rotated by 90 degrees about z: y extent [0, 3] went to x in [-3, 0].
    let bb = g.get_bounding_box(3, vols[0].1).unwrap();
    assert!((bb[0] + 3.0).abs() < 1e-6 && bb[3].abs() < 1e-6, "{bb:?}");

    // Spline through points of a parabola, B-spline with control points.
    let pts: Vec<i32> = (0..5)
        .map(|i| {
            let x = f64::from(i) * 0.25;
            g.occ_add_point(x, x * x, 10.0, 0.0, -1).unwrap()
        })
        .collect();
    let sp = g.occ_add_spline(&pts).unwrap();
    let bs = g.occ_add_bspline(&pts, 3).unwrap();
    g.occ_synchronize().unwrap();
    let (min, max) = g.get_parametrization_bounds(1, sp).unwrap();
    assert_eq!((min.len(), max.len()), (1, 1));
    let ends = g.get_value(1, sp, &[min[0], max[0]]).unwrap();
    assert!(
        (ends[3] - 1.0).abs() < 1e-9 && (ends[4] - 1.0).abs() < 1e-9,
        "{ends:?}"
    );
    // The interpolating spline passes through (0.5, 0.25).
    let (closest, param) = g.get_closest_point(1, sp, &[0.5, 0.25, 10.0]).unwrap();
    assert_eq!(param.len(), 1);
    assert!(
        (closest[0] - 0.5).abs() < 1e-7 && (closest[1] - 0.25).abs() < 1e-7,
        "{closest:?}"
    );
    assert_eq!(g.get_type(1, bs).unwrap(), "BSpline");
}

#[test]
fn surface_filling_and_normal() {
    let g = session();
    let w = circle_wire(&g, 1.0, 0.0);
    let s = g.occ_add_surface_filling(w).unwrap();
    g.occ_synchronize().unwrap();
    let area = g.occ_get_mass(2, s).unwrap();
    assert!(rel(area, PI) < 1e-3, "{area}");
    let (min, max) = g.get_parametrization_bounds(2, s).unwrap();
    let mid = [0.5 * (min[0] + max[0]), 0.5 * (min[1] + max[1])];
    let n = g.get_normal(s, &mid).unwrap();
    assert_eq!(n.len(), 3);
    assert!((n[2].abs() - 1.0).abs() < 1e-6, "{n:?}");
}

#[test]
fn second_order_tet_mesh_of_box() {
    let g = session();
    let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 2.0, 3.0).unwrap();
    g.occ_synchronize().unwrap();
    g.option_set_number("Mesh.MeshSizeMax", 0.5).unwrap();
    g.mesh_generate(3).unwrap();
    g.mesh_set_order(2).unwrap();
    let (types, elems, nodes) = g.mesh_get_elements(3, v).unwrap();
    assert_eq!(types, vec![11]);
    assert!(!elems[0].is_empty());
    assert_eq!(nodes[0].len(), 10 * elems[0].len());
    let (tags, coord, param) = g.mesh_get_nodes(-1, -1, false, false).unwrap();
    assert!(!tags.is_empty());
    assert!(param.is_empty());
    assert_eq!(coord.len(), 3 * tags.len());
    let eps = 1e-9;
    for p in coord.chunks_exact(3) {
        assert!(p[0] >= -eps && p[0] <= 1.0 + eps, "{p:?}");
        assert!(p[1] >= -eps && p[1] <= 2.0 + eps, "{p:?}");
        assert!(p[2] >= -eps && p[2] <= 3.0 + eps, "{p:?}");
    }
    let q = g.mesh_get_element_qualities(&elems[0], "minSICN").unwrap();
    assert_eq!(q.len(), elems[0].len());
    assert!(q.iter().all(|&x| x > 0.0 && x <= 1.0 + 1e-12));
    let vols = g.mesh_get_element_qualities(&elems[0], "volume").unwrap();
    let total: f64 = vols.iter().sum();
    assert!((total - 6.0).abs() < 1e-6, "{total}");
    g.mesh_optimize("", false, 1).unwrap();
    g.mesh_clear().unwrap();
    let (tags, _, _) = g.mesh_get_nodes(-1, -1, false, false).unwrap();
    assert!(tags.is_empty());
}

#[test]
fn transfinite_curve_has_n_nodes() {
    let g = session();
    let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
    g.occ_synchronize().unwrap();
    let edge = g.get_entities(1).unwrap()[0].1;
    let n = 17;
    g.mesh_set_transfinite_curve(edge, n, "Progression", 1.0)
        .unwrap();
    g.mesh_generate(1).unwrap();
    let (tags, coord, param) = g.mesh_get_nodes(1, edge, true, true).unwrap();
    assert_eq!(tags.len(), n as usize);
    assert_eq!(coord.len(), 3 * n as usize);
    assert_eq!(param.len(), n as usize);
    // Interior nodes only:
    let (inner, _, _) = g.mesh_get_nodes(1, edge, false, false).unwrap();
    assert_eq!(inner.len(), n as usize - 2);

    // Transfinite + recombined face gives a structured quad grid.
    g.mesh_clear().unwrap();
    let face = g.get_boundary(&[(3, v)], false, false, false).unwrap()[0].1;
    let (_, edges) = g.get_adjacencies(2, face).unwrap();
    for &e in &edges {
        g.mesh_set_transfinite_curve(e, 5, "Progression", 1.0)
            .unwrap();
    }
    g.mesh_set_transfinite_surface(face, "Left", &[]).unwrap();
    g.mesh_set_recombine(2, face, 45.0).unwrap();
    g.mesh_generate(2).unwrap();
    let (types, elems, _) = g.mesh_get_elements(2, face).unwrap();
    assert_eq!(types, vec![3]);
    assert_eq!(elems[0].len(), 16);
}

#[test]
fn size_field_and_point_sizes() {
    let g = session();
    let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
    g.occ_synchronize().unwrap();
    g.mesh_set_size(&g.get_entities(0).unwrap(), 0.5).unwrap();
    g.mesh_generate(3).unwrap();
    let (_, coarse, _) = g.mesh_get_elements(3, v).unwrap();
    g.mesh_clear().unwrap();
    let f = g.mesh_field_add("Box").unwrap();
    g.mesh_field_set_number(f, "VIn", 0.1).unwrap();
    g.mesh_field_set_number(f, "VOut", 0.5).unwrap();
    for (k, x) in [
        ("XMin", 0.0),
        ("XMax", 0.5),
        ("YMin", 0.0),
        ("YMax", 1.0),
        ("ZMin", 0.0),
        ("ZMax", 1.0),
    ] {
        g.mesh_field_set_number(f, k, x).unwrap();
    }
    let m = g.mesh_field_add("Min").unwrap();
    g.mesh_field_set_numbers(m, "FieldsList", &[f64::from(f)])
        .unwrap();
    g.mesh_field_set_as_background_mesh(m).unwrap();
    g.mesh_generate(3).unwrap();
    let (_, fine, _) = g.mesh_get_elements(3, v).unwrap();
    assert!(
        fine[0].len() > 4 * coarse[0].len(),
        "{} vs {}",
        fine[0].len(),
        coarse[0].len()
    );
}

#[test]
fn physical_groups() {
    let g = session();
    g.add_model("pg").unwrap();
    let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
    g.occ_synchronize().unwrap();
    let faces: Vec<i32> = g.get_entities(2).unwrap().iter().map(|&(_, t)| t).collect();
    let pv = g.add_physical_group(3, &[v], -1, "solid").unwrap();
    let pf = g.add_physical_group(2, &faces[..2], 42, "").unwrap();
    assert_eq!(pf, 42);
    g.set_physical_name(2, pf, "contact").unwrap();
    assert_eq!(g.get_physical_groups(-1).unwrap(), vec![(2, 42), (3, pv)]);
    assert_eq!(
        g.get_entities_for_physical_group(2, 42).unwrap(),
        faces[..2].to_vec()
    );
    assert_eq!(g.get_entities_for_physical_group(3, pv).unwrap(), vec![v]);
}

#[test]
fn write_msh41_and_open() {
    let g = session();
    g.add_model("io").unwrap();
    g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
    g.occ_synchronize().unwrap();
    g.option_set_number("Mesh.MshFileVersion", 4.1).unwrap();
    assert_eq!(g.option_get_number("Mesh.MshFileVersion").unwrap(), 4.1);
    g.option_set_string("General.DefaultFileName", "unused.geo")
        .unwrap();
    assert_eq!(
        g.option_get_string("General.DefaultFileName").unwrap(),
        "unused.geo"
    );
    g.mesh_generate(3).unwrap();
    let (n_nodes, _, _) = g.mesh_get_nodes(-1, -1, false, false).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("box.msh");
    g.write(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.starts_with("$MeshFormat\n4.1"),
        "{}",
        &text[..40.min(text.len())]
    );

    g.clear().unwrap();
    assert!(g.get_entities(-1).unwrap().is_empty());
    g.open(&path).unwrap();
    let (tags, _, _) = g.mesh_get_nodes(-1, -1, false, false).unwrap();
    assert_eq!(tags.len(), n_nodes.len());

    // `open` named the new model after the file; models can be switched.
    g.add_model("second").unwrap();
    assert!(g.get_entities(-1).unwrap().is_empty());
    g.set_current("box").unwrap();
    assert_eq!(g.get_entities(3).unwrap().len(), 1);
}

#[test]
fn invalid_tag_gives_call_error_with_message() {
    let g = session();
    g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
    g.occ_synchronize().unwrap();
    let err = g.occ_get_mass(3, 9999).unwrap_err();
    match &err {
        GmshError::Call {
            call,
            ierr,
            message,
        } => {
            assert_eq!(*call, "gmshModelOccGetMass");
            assert_ne!(*ierr, 0);
            assert!(!message.is_empty());
            assert!(message.contains("9999"), "{message}");
        }
        e => panic!("unexpected error {e:?}"),
    }
    assert!(err.to_string().contains("gmshModelOccGetMass"));
    // The session is still usable after an error.
    assert!((g.occ_get_mass(3, 1).unwrap() - 1.0).abs() < 1e-12);
    assert!(!g.last_error().unwrap().is_empty());
    // Other failing calls.
    assert!(matches!(g.get_type(2, 12345), Err(GmshError::Call { .. })));
    assert!(matches!(
        g.set_current("no such model"),
        Err(GmshError::Call { .. })
    ));
    assert!(matches!(
        g.option_get_number("No.Such.Option"),
        Err(GmshError::Call { .. })
    ));
    assert!(matches!(
        g.open("/nonexistent/file.msh"),
        Err(GmshError::Call { .. })
    ));
    assert!(matches!(
        g.option_set_string("General.DefaultFileName", "a\0b"),
        Err(GmshError::InteriorNul { .. })
    ));
}

#[test]
fn nested_session_on_same_thread_is_an_error() {
    let g = session();
    assert!(matches!(Session::new(), Err(GmshError::NestedSession)));
    drop(g);
    // ... and sessions in sequence work, each starting from an empty model.
    for _ in 0..3 {
        let g = session();
        assert!(g.get_entities(-1).unwrap().is_empty());
        assert!(g.occ_get_entities(-1).unwrap().is_empty());
        let v = g.occ_add_box(0.0, 0.0, 0.0, 1.0, 1.0, 1.0).unwrap();
        g.occ_synchronize().unwrap();
        assert!((g.occ_get_mass(3, v).unwrap() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn two_sessions_from_two_threads() {
    let results: Vec<f64> = std::thread::scope(|s| {
        let handles: Vec<_> = (1..=2)
            .map(|k| {
                s.spawn(move || {
                    let g = Session::new().unwrap();
                    let d = f64::from(k);
                    let v = g.occ_add_box(0.0, 0.0, 0.0, d, d, d).unwrap();
                    g.occ_synchronize().unwrap();
                    g.option_set_number("Mesh.MeshSizeMax", 0.3 * d).unwrap();
                    g.mesh_generate(3).unwrap();
                    let (types, _, _) = g.mesh_get_elements(3, v).unwrap();
                    assert_eq!(types, vec![4]);
                    // The only entities are this thread's: nobody else
                    // touched gmsh while this session was alive.
                    assert_eq!(g.get_entities(3).unwrap(), vec![(3, v)]);
                    g.occ_get_mass(3, v).unwrap()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!((results[0] - 1.0).abs() < 1e-12);
    assert!((results[1] - 8.0).abs() < 1e-12);
}
