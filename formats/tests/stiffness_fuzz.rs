//! Property-based test of the stiffness-file reader: a real
//! stiffness file (the LTCA example's fixture) with bytes flipped, runs of
//! bytes overwritten or the file truncated is read by
//! [`formats::stiffness_file::read`] without a panic: it returns an error or
//! data, and data only with every dataset the size its header gives.
//!
//! Half of the damage lands in the first 8 KiB, where HDF5 keeps the
//! superblock and the object headers, so that not only compliance values
//! are hit. Bounded: [`CASES`] cases, a few seconds in `make test`.

use formats::stiffness_file::{read, StiffnessData};
use proptest::prelude::*;
use std::path::PathBuf;

/// Cases of the property.
const CASES: u32 = 256;

fn fixture() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/02_ltca_fixture/meshes/ltca_fixture/pinion_standard_reduced.stiffness.h5"
    ))
}

#[derive(Debug, Clone)]
enum Damage {
    /// XOR of one byte at a position (mod the length) with a non-zero mask.
    Flip(usize, u8),
    /// A run of bytes overwritten.
    Overwrite(usize, Vec<u8>),
    /// The file cut at a position (mod the length).
    Truncate(usize),
}

fn position() -> impl Strategy<Value = usize> {
    prop_oneof![0..8192usize, any::<usize>()]
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        6 => (position(), 1..=255u8).prop_map(|(k, m)| Damage::Flip(k, m)),
        2 => (position(), proptest::collection::vec(any::<u8>(), 1..16))
            .prop_map(|(k, b)| Damage::Overwrite(k, b)),
        1 => position().prop_map(Damage::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, d: &Damage) {
    let n = bytes.len().max(1);
    match d {
        Damage::Flip(k, m) => {
            if !bytes.is_empty() {
                bytes[k % n] ^= m;
            }
        }
        Damage::Overwrite(k, b) => {
            for (i, x) in b.iter().enumerate() {
                let j = (k % n) + i;
                if j < bytes.len() {
                    bytes[j] = *x;
                }
            }
        }
        Damage::Truncate(k) => bytes.truncate(k % n),
    }
}

/// Data that comes back is consistent with its header.
fn consistent(d: &StiffnessData) -> bool {
    let np = d.points();
    let (ns, no) = (d.solved_teeth.len(), d.offsets.len());
    d.xi.len() == d.grid_face
        && d.eta.len() == d.grid_profile
        && d.position.len() == 3 * np
        && d.normal.len() == 3 * np
        && d.lever.len() == np
        && d.depth_h.len() == ns * np
        && d.total.len() == ns * no * np * np
        && d.local.len() == ns * np * np
        && d.global.len() == ns * no * np * np
}

/// The file a child process reads ([`read_the_file_named_by_the_parent`]).
const CHILD_FILE: &str = "STIFFNESS_FUZZ_FILE";

/// Longest a child may read one damaged file: HDF5 can also loop forever
/// on one (seen once in a `make test` run), which counts as a crash.
const CHILD_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(20);

/// How one read ended, as the child reports it on stdout.
fn child_read(path: &std::path::Path) -> Result<String, String> {
    use std::process::Stdio;
    let mut child = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "read_the_file_named_by_the_parent",
            "--nocapture",
            "--test-threads",
            "1",
        ])
        .env(CHILD_FILE, path)
        .env("RUST_BACKTRACE", "0")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > CHILD_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(format!("CRASH hang (killed after {CHILD_TIMEOUT:?})"));
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    match out.status.code() {
        Some(0) => stdout
            .lines()
            .find_map(|l| l.split_once("OUTCOME "))
            .map(|(_, o)| o.to_string())
            .ok_or_else(|| format!("no outcome: {stdout}")),
        Some(_) => Err(format!("the reader failed or panicked: {stdout}{stderr}")),
        None => Ok(format!("CRASH {:?}", out.status)),
    }
}

/// Reads the file a parent names (does nothing in a normal run): a damaged
/// file can crash the HDF5 C library itself (a signal, not a Rust panic),
/// so each case is read in its own process.
#[test]
fn read_the_file_named_by_the_parent() {
    let Some(path) = std::env::var_os(CHILD_FILE) else {
        return;
    };
    let good = read(&fixture(), None).unwrap();
    match read(std::path::Path::new(&path), None) {
        Ok(d) if !consistent(&d) => println!("OUTCOME INCONSISTENT"),
        Ok(d) if d == good => println!("OUTCOME SAME"),
        Ok(_) => println!("OUTCOME OTHER"),
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains("case"), "no path in: {msg}");
            println!("OUTCOME REFUSED {msg}");
        }
    }
}

#[test]
fn damaged_stiffness_files_are_read_or_refused_without_a_panic() {
    let original = std::fs::read(fixture()).unwrap();
    assert!(consistent(&read(&fixture(), None).unwrap()));
    let dir = tempfile::tempdir().unwrap();
    let counts: std::cell::RefCell<std::collections::BTreeMap<String, usize>> = Default::default();
    let crashes: std::cell::RefCell<Vec<Vec<Damage>>> = Default::default();
    let mut runner = proptest::test_runner::TestRunner::new(ProptestConfig {
        cases: CASES,
        failure_persistence: None,
        ..ProptestConfig::default()
    });
    let case = std::cell::Cell::new(0usize);
    runner
        .run(&proptest::collection::vec(damage(), 1..4), |damages| {
            let mut bytes = original.clone();
            for d in &damages {
                apply(&mut bytes, d);
            }
            case.set(case.get() + 1);
            let path = dir.path().join(format!("case{}.stiffness.h5", case.get()));
            std::fs::write(&path, &bytes).unwrap();
            let outcome = child_read(&path).map_err(TestCaseError::fail)?;
            prop_assert!(
                outcome != "INCONSISTENT",
                "inconsistent data from {damages:?}"
            );
            let kind = outcome.split(' ').next().unwrap().to_string();
            if kind == "CRASH" {
                crashes.borrow_mut().push(damages.clone());
            }
            *counts.borrow_mut().entry(kind).or_default() += 1;
            std::fs::remove_file(&path).unwrap();
            Ok(())
        })
        .unwrap();
    let counts = counts.into_inner();
    eprintln!("stiffness files: {CASES} cases: {counts:?}");
    for c in crashes.borrow().iter().take(5) {
        eprintln!("  HDF5 crashed the process on: {c:?}");
    }
    assert!(
        counts.get("REFUSED").copied().unwrap_or(0) > 0,
        "{counts:?}"
    );
}

/// A header whose grid sizes disagree with the datasets is refused by name.
#[test]
fn dataset_length_that_disagrees_with_the_header_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.stiffness.h5");
    std::fs::copy(fixture(), &path).unwrap();
    {
        let f = formats::stiffness_file::h5().open_rw(&path).unwrap();
        let gp: u32 = f.attr("grid_profile").unwrap().read_scalar().unwrap();
        f.attr("grid_profile")
            .unwrap()
            .write_scalar(&(gp + 1))
            .unwrap();
    }
    let msg = read(&path, None).unwrap_err().to_string();
    assert!(
        msg.contains("grid/eta") && msg.contains("values, expected"),
        "{msg}"
    );
    // Sizes whose product overflows are refused before anything is allocated.
    {
        let f = formats::stiffness_file::h5().open_rw(&path).unwrap();
        for k in ["grid_profile", "grid_face"] {
            f.attr(k).unwrap().write_scalar(&u32::MAX).unwrap();
        }
    }
    let msg = read(&path, None).unwrap_err().to_string();
    assert!(msg.contains("grid_profile = 4294967295"), "{msg}");
}
