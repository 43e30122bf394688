//! Property-based test of the design and scene files: mutated
//! versions of the checked-in files (numbers replaced by any f64 including
//! NaN, ±inf, huge, negative and zero, or by any integer; lines deleted or
//! duplicated; random bytes inserted, including bytes that are not UTF-8)
//! never panic in the parser or the checks, and every refusal is an
//! [`InputError`] that names a field or a parse position.
//!
//! Bounded: [`CASES`] cases per property, a few seconds in `make test`.

use geometry::design::DesignFile;
use geometry::error::InputError;
use geometry::scene::Scene;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

/// Cases per property.
const CASES: u32 = 512;

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn texts(dir: &Path) -> Vec<(PathBuf, String)> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v.into_iter()
        .map(|p| (p.clone(), std::fs::read_to_string(&p).unwrap()))
        .collect()
}

fn designs() -> Vec<(PathBuf, String)> {
    texts(&root().join("reference"))
}

/// Every scene, its design path made absolute so that it loads from anywhere.
fn scenes() -> Vec<(PathBuf, String)> {
    let mut v = texts(&root().join("reference/scenes"));
    for e in std::fs::read_dir(root().join("examples")).unwrap() {
        let p = e.unwrap().path().join("scene.toml");
        if p.exists() {
            let t = std::fs::read_to_string(&p).unwrap();
            v.push((p, t));
        }
    }
    v.into_iter()
        .map(|(p, t)| {
            let dir = p.parent().unwrap().to_path_buf();
            let t = t
                .lines()
                .map(|l| match l.strip_prefix("design = ") {
                    Some(rel) => {
                        let rel: String = toml::from_str::<toml::Value>(&format!("x = {rel}"))
                            .unwrap()["x"]
                            .as_str()
                            .unwrap()
                            .to_string();
                        format!("design = {:?}", dir.join(rel).display().to_string())
                    }
                    None => l.to_string(),
                })
                .collect::<Vec<_>>()
                .join("\n");
            (p, t)
        })
        .collect()
}

/// One change to a file's bytes.
#[derive(Debug, Clone)]
enum Mutation {
    /// The k-th number (mod the count) replaced by a float.
    Float(usize, f64),
    /// The k-th number replaced by an integer.
    Int(usize, i64),
    DeleteLine(usize),
    DuplicateLine(usize),
    /// Bytes inserted at a position (mod the length).
    Bytes(usize, Vec<u8>),
    /// The file cut at a position (mod the length).
    Truncate(usize),
}

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e300),
        Just(-1e300),
        Just(1e-300),
        Just(f64::MIN_POSITIVE),
        -1e3..1e3f64,
        -1e9..1e9f64,
        any::<f64>(),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        8 => (any::<usize>(), any_f64()).prop_map(|(k, v)| Mutation::Float(k, v)),
        1 => (any::<usize>(), any::<i64>()).prop_map(|(k, v)| Mutation::Int(k, v)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(k, b)| Mutation::Bytes(k, b)),
        1 => any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// Byte ranges of the numbers in a TOML text (values after `=` and inside
/// arrays and inline tables, not in strings or comments).
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let (mut in_str, mut in_comment) = (false, false);
    while i < b.len() {
        let c = b[i];
        if in_comment {
            in_comment = c != b'\n';
        } else if in_str {
            if c == b'\\' {
                i += 1;
            } else if c == b'"' {
                in_str = false;
            }
        } else if c == b'#' {
            in_comment = true;
        } else if c == b'"' {
            in_str = true;
        } else if (c.is_ascii_digit() || c == b'-' || c == b'+')
            && i > 0
            && matches!(b[i - 1], b' ' | b'[' | b',' | b'=')
        {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b"+-._".contains(&b[i])) {
                i += 1;
            }
            out.push((start, i));
            continue;
        }
        i += 1;
    }
    out
}

fn toml_float(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        let s = format!("{v:?}");
        if s.contains(['.', 'e']) {
            s
        } else {
            format!("{s}.0")
        }
    }
}

fn apply(text: &str, muts: &[Mutation]) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    for m in muts {
        let t = String::from_utf8_lossy(&bytes).into_owned();
        match m {
            Mutation::Float(k, v) => replace_number(&mut bytes, &t, *k, &toml_float(*v)),
            Mutation::Int(k, v) => replace_number(&mut bytes, &t, *k, &v.to_string()),
            Mutation::DeleteLine(k) | Mutation::DuplicateLine(k) => {
                let mut lines: Vec<&str> = t.split_inclusive('\n').collect();
                if lines.is_empty() {
                    continue;
                }
                let k = k % lines.len();
                if matches!(m, Mutation::DeleteLine(_)) {
                    lines.remove(k);
                } else {
                    lines.insert(k, lines[k]);
                }
                bytes = lines.concat().into_bytes();
            }
            Mutation::Bytes(k, b) => {
                let k = k % (bytes.len() + 1);
                bytes.splice(k..k, b.iter().copied());
            }
            Mutation::Truncate(k) => bytes.truncate(k % (bytes.len() + 1)),
        }
    }
    bytes
}

fn replace_number(bytes: &mut Vec<u8>, text: &str, k: usize, with: &str) {
    // Only on valid text: after a byte mutation the lossy copy's offsets differ.
    if std::str::from_utf8(bytes).is_err() {
        return;
    }
    let nums = numbers(text);
    if nums.is_empty() {
        return;
    }
    let (a, b) = nums[k % nums.len()];
    bytes.splice(a..b, with.bytes());
}

/// A refusal names its field (Invalid) or its line and column (Parse).
fn names_its_cause(e: &InputError, file: &Path) -> Result<(), String> {
    let msg = e.to_string();
    if !msg.contains(&file.display().to_string()) {
        return Err(format!("no file in: {msg}"));
    }
    match e {
        InputError::Invalid { field, limit, .. } => {
            if field.is_empty() || limit.is_empty() {
                return Err(format!("no field or limit in: {msg}"));
            }
        }
        InputError::Parse { message, .. } => {
            if !(message.starts_with("line ") && message.contains(", column ")) {
                return Err(format!("no parse position in: {msg}"));
            }
        }
        InputError::Io { .. } => return Err(format!("a written file is unreadable: {msg}")),
    }
    Ok(())
}

/// Counts of how the cases end, printed at the end of each property.
#[derive(Default, Debug)]
struct Outcomes {
    loaded: std::cell::Cell<usize>,
    invalid: std::cell::Cell<usize>,
    other: std::cell::Cell<usize>,
}

impl Outcomes {
    fn count(&self, r: &Result<(), InputError>) {
        let c = match r {
            Ok(()) => &self.loaded,
            Err(InputError::Invalid { .. }) => &self.invalid,
            Err(_) => &self.other,
        };
        c.set(c.get() + 1);
    }
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: CASES,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

#[test]
fn mutated_design_files_never_panic_and_every_refusal_names_its_cause() {
    let designs = designs();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("design.toml");
    let outcomes = Outcomes::default();
    let mut runner = proptest::test_runner::TestRunner::new(config());
    runner
        .run(
            &(
                0..designs.len(),
                proptest::collection::vec(mutation(), 1..4),
            ),
            |(which, muts)| {
                let bytes = apply(&designs[which].1, &muts);
                std::fs::write(&path, &bytes).unwrap();
                let r = DesignFile::load(&path).and_then(|d| d.to_pair(&path).map(|_| ()));
                if let Ok(text) = std::str::from_utf8(&bytes) {
                    let _ = geometry::design::geometry_text(text);
                }
                outcomes.count(&r);
                if let Err(e) = &r {
                    names_its_cause(e, &path).map_err(TestCaseError::fail)?;
                }
                Ok(())
            },
        )
        .unwrap();
    eprintln!("design files: {CASES} cases, {outcomes:?}");
    assert!(
        outcomes.invalid.get() > 0 && outcomes.other.get() > 0,
        "{outcomes:?}"
    );
}

#[test]
fn mutated_scene_files_never_panic_and_every_refusal_names_its_cause() {
    let scenes = scenes();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    let outcomes = Outcomes::default();
    let mut runner = proptest::test_runner::TestRunner::new(config());
    runner
        .run(
            &(0..scenes.len(), proptest::collection::vec(mutation(), 1..4)),
            |(which, muts)| {
                let bytes = apply(&scenes[which].1, &muts);
                std::fs::write(&path, &bytes).unwrap();
                let r = Scene::load(&path).map(|_| ());
                outcomes.count(&r);
                if let Err(e) = &r {
                    // A design path cut by a mutation names the design file
                    // as unreadable: the scene's own field is then `design`.
                    if let InputError::Io { path: p, .. } = e {
                        if p != &path {
                            return Ok(());
                        }
                    }
                    let file = match e {
                        InputError::Invalid { path: p, .. } | InputError::Parse { path: p, .. } => {
                            p.clone()
                        }
                        InputError::Io { path: p, .. } => p.clone(),
                    };
                    names_its_cause(e, &file).map_err(TestCaseError::fail)?;
                }
                Ok(())
            },
        )
        .unwrap();
    eprintln!("scene files: {CASES} cases, {outcomes:?}");
    assert!(
        outcomes.invalid.get() > 0 && outcomes.other.get() > 0,
        "{outcomes:?}"
    );
}

#[test]
fn the_mutations_find_every_number() {
    let text = "a = 1.5\nb = [1, -2e3, +inf]\nc = \"7\" # 8\nd = { e = 9 }\n";
    let got: Vec<&str> = numbers(text).iter().map(|&(a, b)| &text[a..b]).collect();
    assert_eq!(got, ["1.5", "1", "-2e3", "+inf", "9"]);
    assert_eq!(toml_float(f64::NAN), "nan");
    assert_eq!(toml_float(-1e300), "-1e300");
    assert_eq!(toml_float(3.0), "3.0");
}
