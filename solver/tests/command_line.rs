//! `solver`'s command line, tried as a user would: every subcommand with a
//! random mix of good and bad paths for the scene, `--meshes` and `--out`
//! (missing, a directory where a file belongs, a file where a folder
//! belongs, a scene that is not TOML). A bad argument is refused naming it
//! (the scene first, then the output, then the mesh folder), and a refused
//! run writes no file into the output. With every argument good, `plan`
//! runs (the others are run by the result-set tests).

use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

#[derive(Clone, Copy, Debug, PartialEq)]
enum SceneArg {
    Good,
    Missing,
    Directory,
    NotToml,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum MeshesArg {
    Good,
    Missing,
    File,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum OutArg {
    Fresh,
    File,
}

const SUBCOMMANDS: [&str; 4] = ["plan", "ltca", "dynamic", "sensitivity"];

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

/// Every file under `dir` (directories left out).
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    if let Ok(rd) = std::fs::read_dir(dir) {
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                v.extend(files(&p));
            } else {
                v.push(p);
            }
        }
    }
    v
}

fn case(sub: &str, scene: SceneArg, meshes: MeshesArg, out: OutArg) -> Result<(), TestCaseError> {
    let tmp = tempfile_dir(sub);
    let scene_path = match scene {
        SceneArg::Good => {
            let design = example().join("../../reference/white_paper_20x43.toml");
            let text = std::fs::read_to_string(example().join("scene.toml"))
                .unwrap()
                .replace(
                    "design = \"../../reference/white_paper_20x43.toml\"",
                    &format!("design = {:?}", design.canonicalize().unwrap()),
                )
                .replace("multibody = false", "multibody = true");
            let p = tmp.join("scene.toml");
            std::fs::write(&p, text).unwrap();
            p
        }
        SceneArg::Missing => tmp.join("no_scene.toml"),
        SceneArg::Directory => {
            std::fs::create_dir_all(tmp.join("a_folder.toml")).unwrap();
            tmp.join("a_folder.toml")
        }
        SceneArg::NotToml => {
            std::fs::write(tmp.join("garbage.toml"), "this is [not toml").unwrap();
            tmp.join("garbage.toml")
        }
    };
    let meshes_path = match meshes {
        MeshesArg::Good => example().join("meshes"),
        MeshesArg::Missing => tmp.join("no_meshes"),
        MeshesArg::File => {
            std::fs::write(tmp.join("meshes_file"), "").unwrap();
            tmp.join("meshes_file")
        }
    };
    let out_path = match out {
        OutArg::Fresh => tmp.join("out"),
        OutArg::File => {
            std::fs::write(tmp.join("out_file"), "").unwrap();
            tmp.join("out_file")
        }
    };
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_solver"));
    cmd.arg(sub).arg(&scene_path).arg("--out").arg(&out_path);
    if sub != "plan" {
        cmd.arg("--meshes").arg(&meshes_path);
    }
    let o = cmd
        .env_remove("RUST_BACKTRACE")
        .env_remove("RUST_LIB_BACKTRACE")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let named = |p: &Path| err.contains(&p.display().to_string());
    let what = format!("{sub} scene {scene:?} meshes {meshes:?} out {out:?}");
    let meshes_matter = sub != "plan";
    if scene != SceneArg::Good {
        prop_assert!(
            !o.status.success() && named(&scene_path),
            "{what}: the scene is not named:\n{err}"
        );
    } else if out == OutArg::File {
        prop_assert!(
            !o.status.success() && named(&out_path),
            "{what}: the output is not named:\n{err}"
        );
    } else if meshes_matter && meshes != MeshesArg::Good {
        prop_assert!(
            !o.status.success() && named(&meshes_path),
            "{what}: the mesh folder is not named:\n{err}"
        );
        prop_assert!(
            err.contains("--meshes"),
            "{what}: `--meshes` is not named:\n{err}"
        );
    } else {
        prop_assert!(
            o.status.success(),
            "{what}: a good command line failed:\n{err}"
        );
    }
    if !o.status.success() && out == OutArg::Fresh {
        prop_assert!(
            files(&out_path).is_empty(),
            "{what}: a refused run wrote {:?}",
            files(&out_path)
        );
    }
    let _ = std::fs::remove_dir_all(&tmp);
    Ok(())
}

/// A fresh scratch folder under the target directory.
fn tempfile_dir(sub: &str) -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let p = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "command_line_{sub}_{}_{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&p);
    std::fs::create_dir_all(&p).unwrap();
    p
}

fn scene_arg() -> impl Strategy<Value = SceneArg> {
    prop_oneof![
        3 => Just(SceneArg::Good),
        1 => Just(SceneArg::Missing),
        1 => Just(SceneArg::Directory),
        1 => Just(SceneArg::NotToml),
    ]
}

fn meshes_arg() -> impl Strategy<Value = MeshesArg> {
    prop_oneof![
        Just(MeshesArg::Good),
        Just(MeshesArg::Missing),
        Just(MeshesArg::File)
    ]
}

fn out_arg() -> impl Strategy<Value = OutArg> {
    prop_oneof![2 => Just(OutArg::Fresh), 1 => Just(OutArg::File)]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn a_bad_argument_is_refused_naming_it_and_leaves_no_file(
        sub in proptest::sample::select(&SUBCOMMANDS[..]),
        scene in scene_arg(),
        meshes in meshes_arg(),
        out in out_arg(),
    ) {
        // Every argument good: only `plan` is run here (seconds each
        // otherwise; the result-set tests run the others).
        prop_assume!(sub == "plan" || scene != SceneArg::Good || meshes != MeshesArg::Good || out != OutArg::Fresh);
        case(sub, scene, meshes, out)?;
    }
}

#[test]
fn each_bad_argument_alone_is_refused_naming_it() {
    for sub in SUBCOMMANDS {
        for scene in [SceneArg::Missing, SceneArg::Directory, SceneArg::NotToml] {
            case(sub, scene, MeshesArg::Good, OutArg::Fresh).unwrap();
        }
        case(sub, SceneArg::Good, MeshesArg::Good, OutArg::File).unwrap();
        if sub != "plan" {
            for m in [MeshesArg::Missing, MeshesArg::File] {
                case(sub, SceneArg::Good, m, OutArg::Fresh).unwrap();
            }
        }
    }
    case("plan", SceneArg::Good, MeshesArg::Good, OutArg::Fresh).unwrap();
}
