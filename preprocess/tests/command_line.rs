//! `preprocess`'s command line, tried as a user would: random levels
//! (within and outside the four it knows) and bad paths for the input
//! scene, `--out` and `--meshes` of each subcommand. Each is refused
//! naming the bad argument, before any mesh is made or any file written
//! (a good command line meshes for a minute: the mesh and stiffness tests
//! run those).

#[path = "support/small_scene.rs"]
mod small_scene;

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

const LEVELS: [&str; 4] = ["reduced", "medium", "reference", "both"];

/// A fresh scratch folder holding a good scene, an empty folder and a
/// plain file.
fn scratch() -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let text = small_scene::small_scene_text().replace("ltca = false", "ltca = true");
    let scene = tmp.path().join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    std::fs::write(tmp.path().join("a_file"), "").unwrap();
    (tmp, scene)
}

/// Every file under `dir`.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.is_dir() {
            v.extend(files(&p));
        } else {
            v.push(p);
        }
    }
    v
}

/// Runs `preprocess args`; refused (non-zero exit) naming `named`, with no
/// file under `watch` but those there before.
fn refused(args: &[&str], named: &str, tmp: &Path) -> Result<(), TestCaseError> {
    let before = files(tmp);
    let o = Command::new(env!("CARGO_BIN_EXE_preprocess"))
        .args(args)
        .env_remove("RUST_BACKTRACE")
        .env_remove("RUST_LIB_BACKTRACE")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    prop_assert!(!o.status.success(), "{args:?} ran:\n{err}");
    prop_assert!(err.contains(named), "{args:?}: `{named}` not named:\n{err}");
    prop_assert_eq!(files(tmp), before, "{:?} wrote files", args);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn a_level_outside_the_four_is_refused_naming_the_option(
        sub in proptest::sample::select(&["mesh", "stiffness"][..]),
        level in prop_oneof![
            proptest::sample::select(&LEVELS[..]).prop_map(|l| l.to_uppercase()),
            "[a-z]{0,10}",
            (0u32..10).prop_map(|n| n.to_string()),
        ],
    ) {
        prop_assume!(!LEVELS.contains(&level.as_str()));
        let (tmp, scene) = scratch();
        let t = tmp.path();
        let scene = scene.display().to_string();
        refused(&[sub, &scene, &format!("--level={level}")], "--level", t)?;
    }

    #[test]
    fn a_scene_that_cannot_be_read_is_refused_naming_it(
        sub in proptest::sample::select(&["flanks", "mesh", "stiffness"][..]),
        which in 0usize..3,
    ) {
        let (tmp, _) = scratch();
        let t = tmp.path();
        let bad = match which {
            0 => t.join("no_scene.toml"),
            1 => t.to_path_buf(),
            _ => {
                std::fs::write(t.join("garbage.toml"), "not [toml").unwrap();
                t.join("garbage.toml")
            }
        };
        let bad = bad.display().to_string();
        let out = t.join("out").display().to_string();
        let args: Vec<&str> = match sub {
            "stiffness" => vec![sub, &bad, "--meshes", &out],
            _ => vec![sub, &bad, "--out", &out],
        };
        refused(&args, &bad, t)?;
    }
}

#[test]
fn an_output_that_is_a_file_is_refused_naming_it() {
    let (tmp, scene) = scratch();
    let t = tmp.path();
    let file = t.join("a_file").display().to_string();
    let scene = scene.display().to_string();
    for sub in ["mesh", "flanks"] {
        refused(&[sub, &scene, "--out", &file], &file, t).unwrap();
    }
}

#[test]
fn stiffness_without_meshes_names_the_folder_and_the_command_that_fills_it() {
    let (tmp, scene) = scratch();
    let t = tmp.path();
    let scene = scene.display().to_string();
    let root = t.join("no_meshes").display().to_string();
    refused(
        &["stiffness", &scene, "--meshes", &root],
        &format!("--out {root}`"),
        t,
    )
    .unwrap();
    refused(
        &["stiffness", &scene, "--meshes", &root],
        "no mesh folder",
        t,
    )
    .unwrap();
    let file = t.join("a_file").display().to_string();
    refused(&["stiffness", &scene, "--meshes", &file], &file, t).unwrap();
}
