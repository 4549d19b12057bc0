//! Parameters: the one bound check every number of a config goes through,
//! config parsing with errors that name the field, and `params!`, the
//! declarative macro from which a config's struct, `Default`, serde
//! defaults, bounds and field table all come, one line per field.
//!
//! A bottom layer: it uses only [`crate::num`], [`crate::text`], serde and
//! thiserror, so the map readers, the world, every planner and the
//! simulator check their numbers here and word the errors alike.
//!
//! # One line per field
//!
//! ```text
//! params! {
//!     /// Settings of …
//!     #[derive(Debug, Clone, Copy, PartialEq)]
//!     pub struct PursuitConfig {
//!         pub k_w: f64 = 1.5, "1/s" [> 0.0] label "heading gain k_w" "heading gain: ω = k_w · heading error";
//!         pub brake_fraction: f64 = 0.8, "1" [> 0.0, <= 1.0] "share of …";
//!         pub dwa: DwaConfig = DwaConfig::default(), "" [nested] "the DWA engine";
//!     }
//! }
//! ```
//!
//! Each line is `name: type = default, "unit" [bound] label "label" "doc";`
//! (the label, the field's name in plain words for the panels, may be left
//! out; every planner field has one) with the bound
//! one of `[]` (none), `[> min]`, `[>= min]`, either followed by `, <= max`
//! (else at most [`MAX_PARAM`]), `[nested]` (a config whose fields are
//! listed under `name.` with their own docs) or `[nested of]` (the same,
//! each doc "`field` of the `doc`"). `///` lines above a field add to its
//! rustdoc only; the doc string is what `planlab planners` and the page's
//! parameter panel show (brackets escaped for rustdoc, `\[C\]`, are shown
//! plain). The struct gets `#[serde(default, deny_unknown_fields)]`, a
//! `Default` from the defaults and [`Params`] (the table, and
//! `check_bounds` checking the bounds in field order); rules between fields
//! stay in the config's own `validate`.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::num::{fmt_num, MAX_PARAM};
use crate::text::one_line;

/// Bounds of a number parameter: finite, ≥ `min` (> when `strict`), at
/// most `max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    /// Smallest value (excluded when `strict`).
    pub min: f64,
    /// The value must exceed `min`, not only reach it.
    pub strict: bool,
    /// Largest value.
    pub max: f64,
}

impl Bound {
    /// Finite, ≥ `min`, at most [`MAX_PARAM`].
    pub const fn at_least(min: f64) -> Bound {
        Bound {
            min,
            strict: false,
            max: MAX_PARAM,
        }
    }

    /// Finite, > `min`, at most [`MAX_PARAM`].
    pub const fn above(min: f64) -> Bound {
        Bound {
            min,
            strict: true,
            max: MAX_PARAM,
        }
    }

    /// The same lower bound with `max` as the upper one.
    pub const fn at_most(self, max: f64) -> Bound {
        Bound { max, ..self }
    }

    /// Why `value` breaks the bounds; `None` when it keeps them.
    ///
    /// ```
    /// use planlab_core::params::Bound;
    /// assert_eq!(Bound::above(0.0).problem(0.0).unwrap(), "must be a finite number > 0");
    /// assert_eq!(Bound::at_least(0.0).problem(1e300).unwrap(), "must be at most 1e6");
    /// assert_eq!(Bound::above(0.0).at_most(1.0).problem(1.5).unwrap(), "must be at most 1");
    /// assert!(Bound::at_least(0.0).problem(0.0).is_none());
    /// ```
    pub fn problem(&self, value: f64) -> Option<String> {
        let (min, strict) = (self.min, self.strict);
        let rel = if strict { ">" } else { "≥" };
        if !(value.is_finite() && if strict { value > min } else { value >= min }) {
            Some(format!("must be a finite number {rel} {}", fmt_num(min)))
        } else if value > self.max {
            Some(format!("must be at most {}", fmt_num(self.max)))
        } else {
            None
        }
    }
}

/// Why `value` is not a valid parameter that must be finite, ≥ `min` (>
/// when `strict`) and at most [`MAX_PARAM`]; `None` when it is valid.
/// For messages worded by their section (a unit after the value).
pub fn param_problem(value: f64, min: f64, strict: bool) -> Option<String> {
    let bound = if strict {
        Bound::above(min)
    } else {
        Bound::at_least(min)
    };
    bound.problem(value)
}

/// A parameter or config that is not valid; the text names the field.
/// Each module's error turns it into its own `InvalidParameter`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ParamError {
    /// A number outside its [`Bound`].
    #[error("{name} = {shown}: {problem}", shown = fmt_num(*.value))]
    OutOfRange {
        /// Dotted name (`dwa.v_res`, `v_max (m/s)` …).
        name: String,
        /// Its unit when declared on a `params!` line (else empty); the
        /// world's errors show it (see [`ParamError::unit_named`]).
        unit: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        problem: String,
    },
    /// A config that does not parse, or breaks a rule between fields.
    #[error("{}", one_line(.0))]
    Invalid(String),
}

impl ParamError {
    /// The error with `unit` as the unit of an out-of-range number.
    pub fn with_unit(self, unit: &'static str) -> ParamError {
        match self {
            ParamError::OutOfRange {
                name,
                value,
                problem,
                ..
            } => ParamError::OutOfRange {
                name,
                unit,
                value,
                problem,
            },
            other => other,
        }
    }

    /// The message with the unit after the name, `mass (kg) = -1: …`, as
    /// the world's sections word their errors.
    pub fn unit_named(&self) -> String {
        match self {
            ParamError::OutOfRange {
                name,
                unit,
                value,
                problem,
            } if !unit.is_empty() => format!("{name} ({unit}) = {}: {problem}", fmt_num(*value)),
            other => other.to_string(),
        }
    }
}

/// Checks `value` against `bound`; the error names `name`.
pub fn check_param(name: &str, value: f64, bound: Bound) -> Result<(), ParamError> {
    match bound.problem(value) {
        None => Ok(()),
        Some(problem) => Err(ParamError::OutOfRange {
            name: name.to_string(),
            unit: "",
            value,
            problem,
        }),
    }
}

/// `prefix.field`, or `field` when `prefix` is empty.
pub fn join(prefix: &str, field: &str) -> String {
    if prefix.is_empty() {
        field.to_string()
    } else {
        format!("{prefix}.{field}")
    }
}

/// One field of a config's table (see `params!`).
#[derive(Debug, Clone, Copy)]
pub struct Field {
    /// Field name.
    pub name: &'static str,
    /// Unit ("m", "m/s", "rad", "1" …; empty for words and nested configs).
    pub unit: &'static str,
    /// Its name in plain words for the panels (`heading weight α`); empty
    /// when not given.
    pub label: &'static str,
    /// What it does.
    pub doc: &'static str,
    /// Bounds checked by [`Params::check_bounds`], if any.
    pub bound: Option<Bound>,
    /// Whether it is a nested config, and how its fields are listed.
    pub nested: Nested,
}

/// How a field's own fields are listed.
#[derive(Debug, Clone, Copy)]
pub enum Nested {
    /// Not a config: the field is listed itself.
    No,
    /// A config whose fields are listed as `field.inner` with their docs.
    Config(&'static [Field]),
    /// A config whose fields are listed as `field.inner`, documented as
    /// "`inner` of the `field's doc`" (weight sets of a strategy).
    Of(&'static [Field]),
}

/// A config declared with `params!`: its table and its bounds.
pub trait Params: Serialize + DeserializeOwned + Default {
    /// One entry per field, in declaration order.
    const FIELDS: &'static [Field];

    /// Checks the declared bounds of this config's own number fields in
    /// order (nested configs check theirs in their `validate`); errors name
    /// `prefix.field`.
    fn check_bounds(&self, prefix: &str) -> Result<(), ParamError>;
}

/// One config field, for `planlab planners` and the page's parameter panel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldInfo {
    /// Field name (dotted for nested fields).
    pub name: String,
    /// Unit ("m", "m/s", "rad", "1" …).
    pub unit: String,
    /// Its name in plain words (`heading weight α`; a weight set's field
    /// adds the set's: `heading weight α, deceleration`); the config name
    /// stays `name`, the one papers and scenario files use.
    #[serde(default)]
    pub label: String,
    /// Default value (the paper's).
    pub default: serde_json::Value,
    /// What it does.
    pub doc: String,
    /// Its bounds, if it is a number with bounds (not serialised: the
    /// registry's JSON stays as it was).
    #[serde(skip)]
    pub bound: Option<Bound>,
}

/// A doc string as shown outside rustdoc: its escaped brackets (`\[C\]`,
/// written so for rustdoc's sake) plain.
fn plain_doc(doc: &str) -> String {
    doc.replace("\\[", "[").replace("\\]", "]")
}

/// Calls `out(name, unit, label, doc)` for every leaf of `fields`, nested
/// configs flattened to dotted names under `prefix`.
/// Receives one leaf field: dotted name, unit, label, doc, bounds.
type LeafSink<'a> = dyn FnMut(String, &str, String, String, Option<Bound>) + 'a;

fn flatten(fields: &[Field], prefix: &str, out: &mut LeafSink<'_>) {
    for f in fields {
        let name = join(prefix, f.name);
        match f.nested {
            Nested::No => out(name, f.unit, f.label.to_string(), plain_doc(f.doc), f.bound),
            Nested::Config(inner) => flatten(inner, &name, out),
            Nested::Of(inner) => {
                for g in inner {
                    let label = match (g.label, f.label) {
                        ("", _) => String::new(),
                        (l, "") => l.to_string(),
                        (l, set) => format!("{l}, {set}"),
                    };
                    out(
                        join(&name, g.name),
                        g.unit,
                        label,
                        format!("{} of the {}", g.name, plain_doc(f.doc)),
                        g.bound,
                    );
                }
            }
        }
    }
}

/// The field list of config `T`: every leaf of its table in order (dotted
/// names for nested configs) with its default from `T::default()`.
pub fn field_infos<T: Params>() -> Vec<FieldInfo> {
    let defaults = serde_json::to_value(T::default()).unwrap_or(serde_json::Value::Null);
    let mut out = Vec::new();
    flatten(T::FIELDS, "", &mut |name, unit, label, doc, bound| {
        let default = name
            .split('.')
            .try_fold(&defaults, |v, k| v.get(k))
            .cloned()
            .unwrap_or(serde_json::Value::Null);
        out.push(FieldInfo {
            name,
            unit: unit.to_string(),
            label,
            default,
            doc,
            bound,
        });
    });
    out
}

/// Reads a planner config from JSON: `null` and `{}` give `T::default()`,
/// left-out fields their defaults. On error the message names the planner
/// and the offending field (`dwa.config.alpha: invalid type: string "x",
/// expected f64`). `T` should be `#[serde(default, deny_unknown_fields)]`.
pub fn parse_config<T>(planner: &str, value: &serde_json::Value) -> Result<T, ParamError>
where
    T: DeserializeOwned + Serialize + Default,
{
    use serde_json::Value;
    if value.is_null() {
        return Ok(T::default());
    }
    // serde would also take a struct written as an array of its fields.
    let Value::Object(input) = value else {
        return Err(ParamError::Invalid(format!(
            "{planner}.config must be a JSON object of fields, got {value}"
        )));
    };
    let err = match T::deserialize(value) {
        Ok(t) => return Ok(t),
        Err(e) => e,
    };
    // serde_json does not say which field a type error is in: put the input
    // fields one at a time on top of the defaults; the first that fails is it.
    if let Ok(Value::Object(mut probe)) = serde_json::to_value(T::default()) {
        for (k, v) in input {
            probe.insert(k.clone(), v.clone());
            if let Err(e) = T::deserialize(&Value::Object(probe.clone())) {
                let msg = e.to_string();
                let named = if msg.starts_with("unknown field") {
                    format!(": {msg}")
                } else {
                    format!(".{k}: {msg}")
                };
                return Err(ParamError::Invalid(format!("{planner}.config{named}")));
            }
        }
    }
    Err(ParamError::Invalid(format!("{planner}.config: {err}")))
}

/// Declares a config from one line per field (module doc): the struct with
/// its docs, `Default`, serde defaults and [`Params`].
macro_rules! params {
    (
        $(#[$sattr:meta])*
        $svis:vis struct $name:ident $(< $($gen:ident),+ >)? {
            $(
                $(#[$fattr:meta])*
                $fvis:vis $field:ident : $ty:ty = $default:expr, $unit:literal
                    [$($bound:tt)*] $(label $label:literal)? $doc:literal;
            )*
        }
    ) => {
        $(#[$sattr])*
        #[derive(::serde::Serialize, ::serde::Deserialize)]
        #[serde(default, deny_unknown_fields)]
        $svis struct $name $(< $($gen),+ >)? {
            $(
                #[doc = $doc]
                #[doc = ""]
                $(#[$fattr])*
                #[doc = $crate::params::note!($unit, $default; $($bound)*)]
                $fvis $field: $ty,
            )*
        }

        impl $(< $($gen: Default),+ >)? Default for $name $(< $($gen),+ >)? {
            fn default() -> Self {
                Self {
                    $($field: $default,)*
                }
            }
        }

        impl $(< $($gen: $crate::params::Params),+ >)? $crate::params::Params
            for $name $(< $($gen),+ >)?
        {
            const FIELDS: &'static [$crate::params::Field] = &[
                $(
                    $crate::params::Field {
                        name: stringify!($field),
                        unit: $unit,
                        label: concat!("" $(, $label)?),
                        doc: $doc,
                        bound: $crate::params::bound_of!($($bound)*),
                        nested: $crate::params::nested_of!($ty; $($bound)*),
                    },
                )*
            ];

            fn check_bounds(&self, prefix: &str) -> Result<(), $crate::params::ParamError> {
                $(
                    $crate::params::check_field!(
                        prefix, stringify!($field), $unit, self.$field; $($bound)*
                    );
                )*
                let _ = prefix;
                Ok(())
            }
        }
    };
}
pub(crate) use params;

/// The [`Bound`] a field line's bound tokens declare.
macro_rules! bound {
    (> $min:expr) => {
        $crate::params::Bound::above($min)
    };
    (>= $min:expr) => {
        $crate::params::Bound::at_least($min)
    };
    (> $min:expr, <= $max:expr) => {
        $crate::params::Bound::above($min).at_most($max)
    };
    (>= $min:expr, <= $max:expr) => {
        $crate::params::Bound::at_least($min).at_most($max)
    };
}
pub(crate) use bound;

/// The `Option<Bound>` of a field line (`None` for none or nested).
macro_rules! bound_of {
    () => { None };
    (nested $($of:tt)?) => { None };
    ($($bound:tt)+) => { Some($crate::params::bound!($($bound)+)) };
}
pub(crate) use bound_of;

/// The [`Nested`] of a field line.
macro_rules! nested_of {
    ($ty:ty; nested) => {
        $crate::params::Nested::Config(<$ty as $crate::params::Params>::FIELDS)
    };
    ($ty:ty; nested of) => {
        $crate::params::Nested::Of(<$ty as $crate::params::Params>::FIELDS)
    };
    ($ty:ty; $($other:tt)*) => {
        $crate::params::Nested::No
    };
}
pub(crate) use nested_of;

/// The bound check of one field line: nothing without a bound.
macro_rules! check_field {
    ($prefix:ident, $name:expr, $unit:literal, $value:expr; ) => {};
    ($prefix:ident, $name:expr, $unit:literal, $value:expr; nested $($of:tt)?) => {};
    ($prefix:ident, $name:expr, $unit:literal, $value:expr; $($bound:tt)+) => {
        $crate::params::check_param(
            &$crate::params::join($prefix, $name),
            $value,
            $crate::params::bound!($($bound)+),
        )
        .map_err(|e| e.with_unit($unit))?
    };
}
pub(crate) use check_field;

/// The rustdoc line after a field's doc: unit, default and bounds.
macro_rules! note {
    ($unit:literal, $default:expr; nested $($of:tt)?) => {
        concat!("Default `", stringify!($default), "`.")
    };
    ("", $default:expr; ) => {
        concat!("Default `", stringify!($default), "`.")
    };
    ($unit:literal, $default:expr; ) => {
        concat!("Unit ", $unit, "; default `", stringify!($default), "`.")
    };
    ($unit:literal, $default:expr; $($bound:tt)+) => {
        concat!("Unit ", $unit, "; default `", stringify!($default), "`; `",
            stringify!($($bound)+), "`.")
    };
}
pub(crate) use note;

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    params! {
        /// Inner test config.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct Inner {
            pub a: f64 = 1.0, "m" [>= 0.0] "inner a";
            pub b: bool = true, "bool" [] "inner b (\\[C\\] eq 8)";
        }
    }

    params! {
        /// Outer test config.
        #[derive(Debug, Clone, PartialEq)]
        pub struct Outer<M> {
            pub x: f64 = 2.0, "s" [> 0.0, <= 5.0] "outer x";
            pub inner: Inner = Inner { a: 3.0, b: false }, "" [nested] "the inner";
            pub of: Inner = Inner::default(), "" [nested of] "weights";
            pub motion: M = M::default(), "" [nested] "the motion";
        }
    }

    #[test]
    fn table_flattens_nested_configs_with_defaults() {
        let f = field_infos::<Outer<Inner>>();
        let names: Vec<&str> = f.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(
            names,
            ["x", "inner.a", "inner.b", "of.a", "of.b", "motion.a", "motion.b"]
        );
        assert_eq!(f[1].default, json!(3.0));
        assert_eq!(f[2].default, json!(false));
        assert_eq!(f[1].doc, "inner a");
        assert_eq!(f[2].doc, "inner b ([C] eq 8)");
        assert_eq!(f[3].doc, "a of the weights");
        assert_eq!(f[0].unit, "s");
    }

    #[test]
    fn bounds_are_checked_in_order_and_name_the_field() {
        let mut o = Outer::<Inner>::default();
        assert!(o.check_bounds("p").is_ok());
        o.x = 6.0;
        assert_eq!(
            o.check_bounds("p").unwrap_err().to_string(),
            "p.x = 6: must be at most 5"
        );
        o.x = f64::NAN;
        assert_eq!(
            o.check_bounds("").unwrap_err().to_string(),
            "x = NaN: must be a finite number > 0"
        );
        // Nested configs check their own bounds.
        o.x = 1.0;
        o.inner.a = -1.0;
        assert!(o.check_bounds("p").is_ok());
        assert!(o.inner.check_bounds("p.inner").is_err());
    }

    #[test]
    fn parse_config_names_the_field() {
        let c: Inner = parse_config("t", &json!({"a": 3.0})).unwrap();
        assert_eq!(c.a, 3.0);
        let e = parse_config::<Inner>("t", &json!({"a": 1, "b": "x"}))
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.config.b"), "{e}");
        let e = parse_config::<Inner>("t", &json!({"c": 1}))
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `c`"), "{e}");
        let e = parse_config::<Inner>("t", &json!([1]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("object"), "{e}");
        assert_eq!(
            parse_config::<Inner>("t", &serde_json::Value::Null).unwrap(),
            Inner::default()
        );
    }
}
