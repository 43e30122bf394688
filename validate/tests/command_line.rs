//! `validate`'s command line, tried as a user would: random values of every
//! option whose range does not depend on the scene, within and outside
//! that range, on a scene file that does not exist. Within the range the
//! run goes on to read the scene (and refuses naming it: the documented
//! reason); outside it is refused naming the option, before the scene is
//! even read. Options whose range the scene sets (`--position`, `--row`,
//! `--end-columns`, `--columns`, `--response-tooth`) are checked against
//! it before any FE work by the studies' own tests.

use proptest::prelude::*;
use std::process::Command;

const SCENE: &str = "/nonexistent/scene_for_the_command_line_test.toml";

/// What an option accepts.
#[derive(Clone, Copy, Debug)]
enum Range {
    /// A finite number > 0.
    Positive,
    /// A whole number in [lo, hi].
    Count(u64, u64),
    /// One of these words.
    Choice(&'static [&'static str]),
    /// `I/N` with 0 <= I < N.
    Shard,
}

const LEVELS: &[&str] = &["reduced", "medium", "reference"];

/// (subcommand and its fixed arguments, option, range).
const OPTIONS: &[(&[&str], &str, Range)] = &[
    (&["reference"], "--penalty", Range::Positive),
    (&["reference"], "--penalty-check", Range::Positive),
    (&["reference"], "--start-band-um", Range::Positive),
    (&["reference"], "--search-gap-um", Range::Positive),
    (&["reference"], "--stride", Range::Count(1, u64::MAX)),
    (
        &["reference"],
        "--stride-lightweight",
        Range::Count(1, u64::MAX),
    ),
    (&["reference"], "--block", Range::Count(1, 100_000)),
    (&["reference"], "--memory-gb", Range::Positive),
    (&["reference"], "--shard", Range::Shard),
    (&["reference"], "--level", Range::Choice(LEVELS)),
    (
        &["reference"],
        "--contact",
        Range::Choice(&["two-pass", "pinion-slave"]),
    ),
    (&["convergence"], "--penalty", Range::Positive),
    (&["convergence"], "--penalty-check", Range::Positive),
    (&["convergence"], "--block", Range::Count(1, 100_000)),
    (&["convergence"], "--levels", Range::Choice(LEVELS)),
    (&["convergence"], "--torque-nm", Range::Positive),
    (&["mesh-stiffness"], "--penalty", Range::Positive),
    (&["mesh-stiffness"], "--block", Range::Count(1, 100_000)),
    (&["mesh-stiffness"], "--memory-gb", Range::Positive),
    (&["mesh-stiffness"], "--levels", Range::Choice(LEVELS)),
    (&["line-load"], "--half-width-mm", Range::Positive),
    (&["line-load"], "--line-load-n-per-mm", Range::Positive),
    (&["line-load"], "--levels", Range::Choice(LEVELS)),
    (
        &["line-load"],
        "--member",
        Range::Choice(&["pinion", "wheel"]),
    ),
    (
        &["line-load"],
        "--blank",
        Range::Choice(&["standard", "lightweight"]),
    ),
    (
        &["export-inp", "--position", "0"],
        "--penalty",
        Range::Positive,
    ),
    (
        &["export-inp", "--position", "0"],
        "--threads",
        Range::Count(1, u64::MAX),
    ),
    (
        &["export-inp", "--position", "0"],
        "--level",
        Range::Choice(LEVELS),
    ),
    (
        &["export-inp", "--position", "0"],
        "--contact",
        Range::Choice(&["node-to-surface", "surface-to-surface", "none"]),
    ),
    (
        &["export-inp", "--position", "0"],
        "--wheel-blank",
        Range::Choice(&["standard", "lightweight"]),
    ),
    (&["tradeoff"], "--slices", Range::Count(4, 400)),
    (&["utca"], "--positions", Range::Count(1, 3600)),
    (
        &["report", "--flanks", "f"],
        "--positions",
        Range::Count(1, 3600),
    ),
];

/// Whether `v` lies in `r`.
fn within(r: Range, v: &str) -> bool {
    match r {
        Range::Positive => v.parse::<f64>().is_ok_and(|x| x.is_finite() && x > 0.0),
        Range::Count(lo, hi) => v.parse::<u64>().is_ok_and(|n| (lo..=hi).contains(&n)),
        Range::Choice(words) => words.contains(&v),
        Range::Shard => v
            .split_once('/')
            .and_then(|(i, n)| Some((i.parse::<u64>().ok()?, n.parse::<u64>().ok()?)))
            .is_some_and(|(i, n)| i < n),
    }
}

/// Values for `r`: mostly near and across its limits, some anything.
fn values(r: Range) -> BoxedStrategy<String> {
    let words = prop_oneof![
        Just(String::new()),
        "[a-z-]{1,12}",
        Just("NaN".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e400".to_string()),
    ];
    match r {
        Range::Positive => prop_oneof![
            3 => (-1e6f64..1e6).prop_map(|x| x.to_string()),
            1 => prop_oneof![Just(0.0f64), Just(-0.0), Just(1e-300), Just(f64::MIN_POSITIVE)]
                .prop_map(|x| x.to_string()),
            1 => words,
        ]
        .boxed(),
        Range::Count(lo, hi) => prop_oneof![
            3 => (0u64..2 * hi.min(1 << 20) + 2).prop_map(|n| n.to_string()),
            1 => prop_oneof![Just(lo.saturating_sub(1)), Just(lo), Just(hi), Just(hi.saturating_add(1))]
                .prop_map(|n| n.to_string()),
            1 => (-100i64..0).prop_map(|n| n.to_string()),
            1 => (0.1f64..100.0).prop_map(|x| format!("{x:.2}")),
            1 => words,
        ]
        .boxed(),
        Range::Choice(choices) => prop_oneof![
            2 => proptest::sample::select(choices).prop_map(str::to_string),
            1 => proptest::sample::select(choices).prop_map(|c| c.to_uppercase()),
            1 => words,
        ]
        .boxed(),
        Range::Shard => prop_oneof![
            3 => (0u64..12, 0u64..12).prop_map(|(i, n)| format!("{i}/{n}")),
            1 => words,
        ]
        .boxed(),
    }
}

/// Runs `validate <sub> SCENE <option>=<value>`; its stderr.
fn run(sub: &[&str], option: &str, value: &str) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_validate"))
        .arg(sub[0])
        .arg(SCENE)
        .args(&sub[1..])
        .arg(format!("{option}={value}"))
        .env_remove("RUST_BACKTRACE")
        .env_remove("RUST_LIB_BACKTRACE")
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// One option and value: within → on to the scene; outside → refused
/// naming the option, the scene not read.
fn check(sub: &[&str], option: &str, r: Range, value: &str) -> Result<(), TestCaseError> {
    let (code, err) = run(sub, option, value);
    prop_assert!(
        code.is_some_and(|c| c != 0),
        "{sub:?} {option}={value}: exit {code:?}"
    );
    if within(r, value) {
        prop_assert!(
            err.contains(SCENE) && err.contains("cannot read"),
            "{sub:?} {option}={value:?} is within its range but was refused:\n{err}"
        );
    } else {
        prop_assert!(
            err.contains(option) && !err.contains("cannot read"),
            "{sub:?} {option}={value:?} is outside its range but was not refused naming it before reading the scene:\n{err}"
        );
    }
    Ok(())
}

/// An option (its index in [`OPTIONS`]) and a value drawn for its range.
fn option_and_value() -> impl Strategy<Value = (usize, String)> {
    (0..OPTIONS.len()).prop_flat_map(|k| (Just(k), values(OPTIONS[k].2)))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn every_option_is_refused_outside_its_range_naming_it_and_accepted_within(
        (k, value) in option_and_value(),
    ) {
        let (sub, option, r) = OPTIONS[k];
        check(sub, option, r, &value)?;
    }
}

/// Every option at its limits and just beyond, once each (the random test
/// samples only some options per run).
#[test]
fn every_option_at_and_beyond_its_limits() {
    for &(sub, option, r) in OPTIONS {
        let cases: Vec<String> = match r {
            Range::Positive => ["1e-9", "2.5", "0", "-1", "NaN", "inf", ""]
                .map(String::from)
                .to_vec(),
            Range::Count(lo, hi) => {
                let mut v = vec![
                    lo.to_string(),
                    hi.to_string(),
                    lo.saturating_sub(1).to_string(),
                    "-1".into(),
                    "1.5".into(),
                ];
                if hi < u64::MAX {
                    v.push((hi + 1).to_string());
                }
                v
            }
            Range::Choice(c) => c
                .iter()
                .map(|s| s.to_string())
                .chain(["bogus".into(), String::new()])
                .collect(),
            Range::Shard => ["0/1", "2/3", "3/3", "0/0", "1", "a/b"]
                .map(String::from)
                .to_vec(),
        };
        for v in &cases {
            check(sub, option, r, v).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
