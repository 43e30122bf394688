//! The reference's contact-pattern file for ParaView, read back by an
//! independent reader (meshio, from the project's .venv).

use std::process::Command;

/// Three flank nodes with their pressures: meshio reads the same points,
/// three vertex cells and the pressure in MPa.
#[test]
fn pattern_vtu_reads_back_in_meshio() {
    let pts = [
        ([0.01, 0.02, 0.03], 1.0e8),
        ([0.04, 0.05, 0.06], 2.5e8),
        ([-0.01, 0.0, 0.07], 0.0),
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pattern.vtu");
    std::fs::write(
        &path,
        validate::reference::reference_stage::pattern_vtu(&pts),
    )
    .unwrap();
    let python = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../.venv/bin/python");
    let script = "import sys, meshio\n\
m = meshio.read(sys.argv[1])\n\
print(len(m.points), sum(len(c.data) for c in m.cells), m.cells[0].type)\n\
print(' '.join(repr(float(v)) for v in m.point_data['pressure_mpa']))\n\
print(' '.join(repr(float(v)) for v in m.points.flatten()))\n";
    let out = Command::new(&python)
        .arg("-c")
        .arg(script)
        .arg(&path)
        .output()
        .expect("the project's .venv (make setup)");
    assert!(
        out.status.success(),
        "meshio failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "3 3 vertex");
    let p: Vec<f64> = lines[1].split(' ').map(|v| v.parse().unwrap()).collect();
    assert_eq!(p, vec![100.0, 250.0, 0.0]);
    let x: Vec<f64> = lines[2].split(' ').map(|v| v.parse().unwrap()).collect();
    let want: Vec<f64> = pts.iter().flat_map(|(p, _)| p.iter().copied()).collect();
    assert_eq!(x, want);
}
