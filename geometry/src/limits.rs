//! Every limit of every scene and design field, as data: one [`Limit`] per
//! rule, naming the field as its refusal names it, the file it lives in,
//! the rule, the unit and why. The checks ([`crate::scene_checks`],
//! [`crate::design_file`], [`crate::scene_bearings`], [`crate::scene_lumped`],
//! [`crate::scene_contact_law`], [`crate::scene_sensitivity`],
//! [`crate::misalignment`], [`crate::pair`]) test values against these
//! entries and build their refusals from them, so [`markdown_table`] (the
//! table of `docs/limits.md`) lists what they check and nothing else.
//!
//! Field patterns: `<member>` stands for `pinion` or `wheel` and `<mate>` for
//! the other one, `<level>` for a mesh level (`reduced_order`, `medium`,
//! `reference`), `[i]` and `[j]` for an index. Every number of a range must
//! also be finite: NaN and ±∞ are refused.

use crate::error::InputError;
use std::path::Path;

/// Declares each entry as a `pub static` and lists them all, in
/// declaration order, in `LIMITS`.
macro_rules! limits {
    ($($name:ident = $e:expr;)*) => {
        $(pub static $name: Limit = $e;)*
        /// Every entry of this file, in declaration order.
        pub static LIMITS: &[&Limit] = &[$(&$name),*];
    };
}

pub mod bearings;
pub mod design;
pub mod lumped;
pub mod multibody;
pub mod scene;

/// The rule of a name that becomes a directory name
/// ([`crate::design_file::check_plain_name`]).
pub const PLAIN_NAME: &str = "plain name: not empty, at most 100 characters, no `/`, `\\` or `..`, not `.`, no control characters";
/// Why names are plain.
pub const PLAIN_NAME_WHY: &str = "it becomes a directory name";

/// The file a field lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum File {
    Scene,
    Design,
}

impl File {
    pub fn name(self) -> &'static str {
        match self {
            File::Scene => "scene",
            File::Design => "design",
        }
    }
}

/// One rule of one field (or of each field a pattern stands for).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    pub file: File,
    /// The field as the refusal names it (a pattern, see the module docs).
    pub field: &'static str,
    pub rule: Rule,
    /// Unit of the field (empty: a pure number).
    pub unit: &'static str,
    /// Why the limit is where it is (empty where the code gives no reason).
    pub why: &'static str,
}

/// What a field must satisfy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rule {
    /// A number (or each number of a list, or a count of entries) in a range.
    Range(Range),
    /// A rule that is not a range (a name, an order, a combination of fields).
    Words(&'static str),
    /// A limit computed from the design or other fields, in words.
    Derived(&'static str),
}

/// A range with its ends, what is measured, and how the refusal says it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    pub lo: End,
    pub hi: End,
    pub number: Number,
    /// The field is a list and every entry must lie in the range.
    pub list: bool,
    /// 0 is admitted too (a switch: "use the default").
    pub or_zero: bool,
    /// The range bounds a quantity derived from the field (and others),
    /// not the field's value itself.
    pub quantity: Option<&'static str>,
    pub says: Says,
}

/// One end of a range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum End {
    /// No limit on this side.
    Unbounded,
    /// A number; `exp` shows it as `1e6` rather than `1000000`.
    Num { value: f64, closed: bool, exp: bool },
    /// Another field of the scene or design: `scale` × field + `offset`.
    Field {
        field: &'static str,
        scale: f64,
        offset: f64,
        closed: bool,
    },
    /// A quantity derived from the input, in words.
    Derived { what: &'static str, closed: bool },
}

/// What is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Number {
    Real,
    Integer,
    OddInteger,
    /// The number of entries of a list.
    Count,
}

/// How the refusal states the limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Says {
    /// "must lie in `interval``suffix`".
    LieIn(&'static str),
    /// "each must lie in `interval``suffix`".
    EachLieIn(&'static str),
    /// This text.
    Text(&'static str),
    /// The check builds the text (it holds values of the input).
    Computed,
}

/// A closed end at `v`.
pub const fn closed(v: f64) -> End {
    End::Num {
        value: v,
        closed: true,
        exp: false,
    }
}

/// An open end at `v`.
pub const fn open(v: f64) -> End {
    End::Num {
        value: v,
        closed: false,
        exp: false,
    }
}

/// A closed end at `v`, shown as `1e6`.
pub const fn closed_e(v: f64) -> End {
    End::Num {
        value: v,
        closed: true,
        exp: true,
    }
}

/// An open end at `v`, shown as `1e6`.
pub const fn open_e(v: f64) -> End {
    End::Num {
        value: v,
        closed: false,
        exp: true,
    }
}

/// A closed end at `scale` × `field` + `offset`.
pub const fn closed_at(scale: f64, field: &'static str, offset: f64) -> End {
    End::Field {
        field,
        scale,
        offset,
        closed: true,
    }
}

/// An open end at `field`.
pub const fn open_at(field: &'static str) -> End {
    End::Field {
        field,
        scale: 1.0,
        offset: 0.0,
        closed: false,
    }
}

/// A closed end at a derived quantity.
pub const fn closed_derived(what: &'static str) -> End {
    End::Derived { what, closed: true }
}

/// An open end at a derived quantity.
pub const fn open_derived(what: &'static str) -> End {
    End::Derived {
        what,
        closed: false,
    }
}

const fn range(lo: End, hi: End, number: Number) -> Range {
    Range {
        lo,
        hi,
        number,
        list: false,
        or_zero: false,
        quantity: None,
        says: Says::Computed,
    }
}

/// A real number in [lo, hi] (each end as given).
pub const fn real(lo: End, hi: End) -> Range {
    range(lo, hi, Number::Real)
}

/// An integer in [lo, hi].
pub const fn integer(lo: End, hi: End) -> Range {
    range(lo, hi, Number::Integer)
}

/// An odd integer in [lo, hi].
pub const fn odd(lo: End, hi: End) -> Range {
    range(lo, hi, Number::OddInteger)
}

/// A number of entries in [lo, hi].
pub const fn count(lo: End, hi: End) -> Range {
    range(lo, hi, Number::Count)
}

/// A rule in words.
pub const fn words(text: &'static str) -> Rule {
    Rule::Words(text)
}

/// A derived limit in words.
pub const fn derived(text: &'static str) -> Rule {
    Rule::Derived(text)
}

impl Range {
    /// Every entry of the list must lie in the range.
    pub const fn each(self) -> Range {
        Range { list: true, ..self }
    }
    /// 0 is admitted too.
    pub const fn or_zero(self) -> Range {
        Range {
            or_zero: true,
            ..self
        }
    }
    /// The range bounds `quantity`, derived from the field.
    pub const fn of(self, quantity: &'static str) -> Range {
        Range {
            quantity: Some(quantity),
            ..self
        }
    }
    /// Refused as "must lie in `interval``suffix`".
    pub const fn lie_in(self, suffix: &'static str) -> Rule {
        Rule::Range(Range {
            says: Says::LieIn(suffix),
            ..self
        })
    }
    /// Refused as "each must lie in `interval``suffix`".
    pub const fn each_lie_in(self, suffix: &'static str) -> Rule {
        Rule::Range(Range {
            says: Says::EachLieIn(suffix),
            ..self
        })
    }
    /// Refused with `text`.
    pub const fn says(self, text: &'static str) -> Rule {
        Rule::Range(Range {
            says: Says::Text(text),
            ..self
        })
    }
    /// Refused with a text the check builds.
    pub const fn computed(self) -> Rule {
        Rule::Range(self)
    }

    /// Whether `v` lies in the range; `ends` are the values of the ends
    /// that are not numbers (fields, derived quantities), low end first.
    pub fn admits(&self, v: f64, ends: &[f64]) -> bool {
        if !v.is_finite() {
            return false;
        }
        if self.or_zero && v == 0.0 {
            return true;
        }
        let mut ends = ends.iter().copied();
        let mut end = |e: &End| -> Option<(f64, bool)> {
            match *e {
                End::Unbounded => None,
                End::Num { value, closed, .. } => Some((value, closed)),
                End::Field { closed, .. } | End::Derived { closed, .. } => Some((
                    ends.next()
                        .expect("the check gives the value of every end that is not a number"),
                    closed,
                )),
            }
        };
        let lo_ok = end(&self.lo).is_none_or(|(e, c)| if c { v >= e } else { v > e });
        let hi_ok = end(&self.hi).is_none_or(|(e, c)| if c { v <= e } else { v < e });
        let number_ok = match self.number {
            Number::Real => true,
            Number::Integer | Number::Count => v.fract() == 0.0,
            Number::OddInteger => v.fract() == 0.0 && v.rem_euclid(2.0) == 1.0,
        };
        lo_ok && hi_ok && number_ok
    }

    /// The interval as the messages and the table write it: `(0, 5]`,
    /// `> 0`, `≤ 5`, with other fields in backticks.
    pub fn interval(&self) -> String {
        let lo = end_text(&self.lo);
        let hi = end_text(&self.hi);
        match (&self.lo, &self.hi) {
            (End::Unbounded, End::Unbounded) => "finite".into(),
            (l, End::Unbounded) => format!("{} {lo}", if is_closed(l) { "≥" } else { ">" }),
            (End::Unbounded, h) => format!("{} {hi}", if is_closed(h) { "≤" } else { "<" }),
            (l, h) => format!(
                "{}{lo}, {hi}{}",
                if is_closed(l) { "[" } else { "(" },
                if is_closed(h) { "]" } else { ")" }
            ),
        }
    }

    /// The rule as the table writes it.
    pub fn text(&self) -> String {
        let interval = self.interval();
        let both = !matches!(self.lo, End::Unbounded) && !matches!(self.hi, End::Unbounded);
        let what = match (self.number, self.list) {
            (Number::Real, false) => "",
            (Number::Real, true) => "each",
            (Number::Integer, false) => "integer",
            (Number::Integer, true) => "each an integer",
            (Number::OddInteger, _) => "odd integer",
            (Number::Count, _) => "number of entries",
        };
        let mut text = match (what, both) {
            ("", _) => interval,
            (w, true) => format!("{w} in {interval}"),
            (w, false) => format!("{w} {interval}"),
        };
        if self.or_zero {
            text = format!("0, or {text}");
        }
        if let Some(q) = self.quantity {
            text = format!("{q}: {text}");
        }
        text
    }
}

fn is_closed(e: &End) -> bool {
    match *e {
        End::Unbounded => false,
        End::Num { closed, .. } | End::Field { closed, .. } | End::Derived { closed, .. } => closed,
    }
}

/// A number as the messages write it.
fn num(v: f64, exp: bool) -> String {
    if exp {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

fn end_text(e: &End) -> String {
    match *e {
        End::Unbounded => String::new(),
        End::Num { value, exp, .. } => num(value, exp),
        End::Field {
            field,
            scale,
            offset,
            ..
        } => {
            let mut t = if scale == 1.0 {
                format!("`{field}`")
            } else {
                format!("{scale} × `{field}`")
            };
            if offset < 0.0 {
                t.push_str(&format!(" − {}", -offset));
            } else if offset > 0.0 {
                t.push_str(&format!(" + {offset}"));
            }
            t
        }
        End::Derived { what, .. } => what.into(),
    }
}

impl Limit {
    /// A field of the scene file.
    pub const fn scene(field: &'static str, unit: &'static str, rule: Rule) -> Limit {
        Limit {
            file: File::Scene,
            field,
            rule,
            unit,
            why: "",
        }
    }

    /// A field of the design file.
    pub const fn design(field: &'static str, unit: &'static str, rule: Rule) -> Limit {
        Limit {
            file: File::Design,
            field,
            rule,
            unit,
            why: "",
        }
    }

    /// The same with its reason.
    pub const fn why(self, why: &'static str) -> Limit {
        Limit { why, ..self }
    }

    /// The range of a [`Rule::Range`] entry.
    pub fn range(&self) -> Option<&Range> {
        match &self.rule {
            Rule::Range(r) => Some(r),
            _ => None,
        }
    }

    /// The limit as the refusal of a range with numbers at both ends says
    /// it; `None` for a text the check builds and for rules in words.
    pub fn says(&self) -> Option<String> {
        let r = self.range()?;
        match r.says {
            Says::LieIn(suffix) => Some(format!("must lie in {}{suffix}", r.interval())),
            Says::EachLieIn(suffix) => Some(format!("each must lie in {}{suffix}", r.interval())),
            Says::Text(t) => Some(t.into()),
            Says::Computed => None,
        }
    }

    /// Whether `v` satisfies the range (see [`Range::admits`]).
    pub fn admits(&self, v: f64, ends: &[f64]) -> bool {
        self.range()
            .expect("admits is asked of a range")
            .admits(v, ends)
    }

    /// The refusal of `value` in `field` (the entry's field or one it
    /// stands for) with `limit`.
    pub fn refuse(&self, path: &Path, field: &str, value: String, limit: String) -> InputError {
        InputError::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            value,
            limit,
        }
    }

    /// `v` in the range of this entry's own field, else its refusal.
    pub fn check(&self, path: &Path, v: f64) -> Result<(), InputError> {
        self.check_at(path, self.field, v)
    }

    /// `v` of `field` (one the entry stands for) in the range, else its
    /// refusal with the entry's text.
    pub fn check_at(&self, path: &Path, field: &str, v: f64) -> Result<(), InputError> {
        self.check_ends(path, field, v, &[])
    }

    /// `v` of `field` in the range whose ends that are not numbers have
    /// the values `ends`, else the refusal with the entry's text.
    pub fn check_ends(
        &self,
        path: &Path,
        field: &str,
        v: f64,
        ends: &[f64],
    ) -> Result<(), InputError> {
        self.check_with(path, field, v, ends, || self.text_of_refusal())
    }

    /// The entry's text of a refusal ([`Limit::says`]).
    pub fn text_of_refusal(&self) -> String {
        self.says()
            .expect("a range whose check builds its text is checked with check_with")
    }

    /// The integer `n` of `field` in the range, else its refusal with the
    /// entry's text (the value written as the integer it is).
    pub fn check_integer(&self, path: &Path, field: &str, n: usize) -> Result<(), InputError> {
        if self.admits(n as f64, &[]) {
            Ok(())
        } else {
            Err(self.refuse(path, field, n.to_string(), self.text_of_refusal()))
        }
    }

    /// The time steps of a run of `time_s` at steps up to `max_step_s`
    /// within this entry's range (a time-steps limit on the step's field),
    /// else its refusal naming the count.
    pub fn check_time_steps(
        &self,
        path: &Path,
        time_s: f64,
        max_step_s: f64,
    ) -> Result<(), InputError> {
        let steps = time_s / max_step_s;
        if self.admits(steps, &[]) {
            return Ok(());
        }
        Err(self.refuse(
            path,
            self.field,
            max_step_s.to_string(),
            format!(
                "too small: {steps:.3e} steps over {time_s} s, at most {:.0e}",
                crate::scene_checks::MAX_TIME_STEPS
            ),
        ))
    }

    /// `v` of `field` in the range whose ends that are not numbers have
    /// the values `ends`, else the refusal with `limit`.
    pub fn check_with(
        &self,
        path: &Path,
        field: &str,
        v: f64,
        ends: &[f64],
        limit: impl FnOnce() -> String,
    ) -> Result<(), InputError> {
        if self.admits(v, ends) {
            Ok(())
        } else {
            Err(self.refuse(path, field, v.to_string(), limit()))
        }
    }

    /// The rule as the table writes it.
    pub fn rule_text(&self) -> String {
        match &self.rule {
            Rule::Range(r) => r.text(),
            Rule::Words(w) => (*w).into(),
            Rule::Derived(d) => format!("derived: {d}"),
        }
    }

    /// The table of the file the field is in: its path up to the last
    /// name (`multibody.impact`, `<member>.material`), empty at the top
    /// level.
    pub fn table(&self) -> &'static str {
        let path = self.field.split(' ').next().unwrap_or(self.field);
        path.rfind('.').map_or("", |i| &path[..i])
    }
}

/// Every entry: the scene's, then the design's.
pub fn all() -> impl Iterator<Item = &'static Limit> {
    scene::LIMITS
        .iter()
        .chain(multibody::LIMITS)
        .chain(bearings::LIMITS)
        .chain(lumped::LIMITS)
        .chain(design::LIMITS)
        .copied()
}

/// Every entry in one markdown table (file, field, rule, unit, why):
/// scene before design, grouped by table, sorted by table and field; the
/// rules of one field in declaration order.
pub fn markdown_table() -> String {
    let mut rows: Vec<&Limit> = all().collect();
    rows.sort_by_key(|l| (l.file, l.table(), l.field));
    let cell = |s: &str| s.replace('|', "\\|");
    let mut out =
        String::from("| file | field | rule / limit | unit | why |\n|---|---|---|---|---|\n");
    for l in rows {
        out.push_str(&format!(
            "| {} | `{}` | {} | {} | {} |\n",
            l.file.name(),
            cell(l.field),
            cell(&l.rule_text()),
            if l.unit.is_empty() { "–" } else { l.unit },
            cell(l.why),
        ));
    }
    out
}
