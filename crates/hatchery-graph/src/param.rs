//! Typed node parameters: kinds with defaults and ranges, values, and their conversion
//! from and to the raw RON values of a graph file.
//!
//! Over 600 lines: parameter kinds, values, their RON conversion and command-line parsing, the
//! relative data values and their tests are one vocabulary; the typed declaration of a kind's
//! parameters is node_params.rs.

use crate::error::ParamError;
use std::collections::BTreeMap;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What a parameter holds, with its range where it has one.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamKind {
    Float {
        min: f64,
        max: f64,
    },
    Int {
        min: i64,
        max: i64,
    },
    Bool,
    /// One of a fixed set of names.
    Choice(&'static [&'static str]),
    /// RGBA, each channel in 0..=1.
    Color,
    Vec3,
    /// A file path; relative paths in a graph file are relative to that file's folder.
    Path,
    Text,
}

impl ParamKind {
    /// Short description of the expected value, for error messages and docs.
    pub fn describe(&self) -> String {
        match self {
            ParamKind::Float { min, max } => format!("a number in [{min}, {max}]"),
            ParamKind::Int { min, max } => format!("an integer in [{min}, {max}]"),
            ParamKind::Bool => "true or false".into(),
            ParamKind::Choice(names) => format!("one of {}", quote_list(names)),
            ParamKind::Color => "a colour [r, g, b, a] with channels in [0, 1]".into(),
            ParamKind::Vec3 => "a vector [x, y, z]".into(),
            ParamKind::Path => "a file path string".into(),
            ParamKind::Text => "a string".into(),
        }
    }

    /// Name of the kind in the node catalogue.
    pub fn type_name(&self) -> &'static str {
        match self {
            ParamKind::Float { .. } => "float",
            ParamKind::Int { .. } => "int",
            ParamKind::Bool => "bool",
            ParamKind::Choice(_) => "choice",
            ParamKind::Color => "color",
            ParamKind::Vec3 => "vec3",
            ParamKind::Path => "path",
            ParamKind::Text => "text",
        }
    }
}

pub(crate) fn quote_list(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One parameter of a node kind: name, kind, default and a one-line doc.
#[derive(Clone, Debug)]
pub struct ParamSpec {
    pub name: &'static str,
    pub kind: ParamKind,
    pub default: ParamValue,
    pub doc: &'static str,
    /// For a path parameter that reads data: which kind of file (a graph input of that kind
    /// may be bound to it, see [`crate::inputs`]).
    pub reads: Option<crate::input_kind::InputKind>,
    /// A float in data units that may also be given relative to the connected volume's values
    /// (`"percentile(60)"`, `"range(0.3)"`, `"otsu"`; see [`RelativeValue`]).
    pub relative: bool,
    /// The editor widget for a parameter that is more than a number or a line of text.
    pub widget: Option<Widget>,
    /// A length in pixels of the figure as designed (a hatching cell, a line width, a font
    /// size): multiplied by the render's pixel scale ([`crate::ExecContext::pixel_scale`]), so a
    /// render at k times the size is the designed figure at k times the resolution.
    pub pixels: bool,
}

/// An editor widget a parameter asks for (the editor's inspector picks it by this, not by the
/// node kind).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Widget {
    /// Control points of a 1-D transfer function, drawn as a curve over the data's histogram.
    TransferFunction,
    /// Nodes of a style transfer function (value → style, opacity), with the styles' spheres.
    StyleTransferFunction,
    /// A list of lit-sphere styles with their thumbnails.
    StyleList,
    /// The object table of a label volume (one row per object).
    ObjectTable,
    /// A WGSL shader file (the file picker shows .wgsl).
    ShaderFile,
}

impl ParamSpec {
    pub fn float(name: &'static str, default: f64, min: f64, max: f64, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Float { min, max },
            default: ParamValue::Float(default),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn int(name: &'static str, default: i64, min: i64, max: i64, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Int { min, max },
            default: ParamValue::Int(default),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn bool(name: &'static str, default: bool, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Bool,
            default: ParamValue::Bool(default),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn choice(
        name: &'static str,
        default: &'static str,
        choices: &'static [&'static str],
        doc: &'static str,
    ) -> Self {
        debug_assert!(choices.contains(&default));
        Self {
            name,
            kind: ParamKind::Choice(choices),
            default: ParamValue::Choice(default.into()),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn color(name: &'static str, default: [f64; 4], doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Color,
            default: ParamValue::Color(default),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn vec3(name: &'static str, default: [f64; 3], doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Vec3,
            default: ParamValue::Vec3(default),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn path(name: &'static str, default: &'static str, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Path,
            default: ParamValue::Path(default.into()),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }
    pub fn text(name: &'static str, default: &'static str, doc: &'static str) -> Self {
        Self {
            name,
            kind: ParamKind::Text,
            default: ParamValue::Text(default.into()),
            doc,
            reads: None,
            relative: false,
            widget: None,
            pixels: false,
        }
    }

    /// Marks a path parameter as reading a data file of `kind` (graph inputs bind to it).
    pub fn reads(mut self, kind: crate::input_kind::InputKind) -> Self {
        self.reads = Some(kind);
        self
    }

    /// Asks the editor for `widget` to edit this parameter.
    pub fn widget(mut self, widget: Widget) -> Self {
        self.widget = Some(widget);
        self
    }

    /// Marks a float or integer as a length in pixels of the designed figure (see
    /// [`ParamSpec::pixels`](#structfield.pixels)).
    pub fn pixels(mut self) -> Self {
        debug_assert!(matches!(
            self.kind,
            ParamKind::Float { .. } | ParamKind::Int { .. }
        ));
        self.pixels = true;
        self
    }

    /// Lets this float (a value in data units) be given relative to the connected volume.
    pub fn relative(mut self) -> Self {
        debug_assert!(matches!(self.kind, ParamKind::Float { .. }));
        self.relative = true;
        self
    }

    /// Converts a raw value from a graph file, checking type and range.
    pub fn convert(&self, raw: &ron::Value) -> Result<ParamValue, ParamError> {
        let found = describe_raw(raw);
        let wrong = || format!("expected {}, found {found}", self.kind.describe());
        let value = match &self.kind {
            ParamKind::Float { .. } if self.relative && as_str(raw).is_some() => {
                let text = as_str(raw).unwrap_or_default();
                ParamValue::Relative(
                    RelativeValue::parse(text).map_err(|e| {
                    format!("expected a number or a value relative to the data, found the string \"{text}\": {e}")
                })?,
                    text.trim().to_owned(),
                )
            }
            ParamKind::Float { .. } => ParamValue::Float(as_f64(raw).ok_or_else(wrong)?),
            ParamKind::Int { .. } => ParamValue::Int(as_i64(raw).ok_or_else(wrong)?),
            ParamKind::Bool => match raw {
                ron::Value::Bool(b) => ParamValue::Bool(*b),
                _ => return Err(wrong().into()),
            },
            ParamKind::Choice(_) => ParamValue::Choice(as_str(raw).ok_or_else(wrong)?.to_owned()),
            ParamKind::Path => ParamValue::Path(as_str(raw).ok_or_else(wrong)?.to_owned()),
            ParamKind::Text => ParamValue::Text(as_str(raw).ok_or_else(wrong)?.to_owned()),
            ParamKind::Color => {
                let v = as_floats(raw)
                    .filter(|v| v.len() == 4 || v.len() == 3)
                    .ok_or_else(wrong)?;
                ParamValue::Color([v[0], v[1], v[2], v.get(3).copied().unwrap_or(1.0)])
            }
            ParamKind::Vec3 => {
                let v = as_floats(raw).filter(|v| v.len() == 3).ok_or_else(wrong)?;
                ParamValue::Vec3([v[0], v[1], v[2]])
            }
        };
        self.check(&value)?;
        Ok(value)
    }

    /// Checks a typed value against this spec's kind and range.
    pub fn check(&self, value: &ParamValue) -> Result<(), ParamError> {
        match (&self.kind, value) {
            (ParamKind::Float { min, max }, ParamValue::Float(v)) => {
                if !v.is_finite() || v < min || v > max {
                    return Err(format!("value {v} is out of range [{min}, {max}]").into());
                }
            }
            (ParamKind::Int { min, max }, ParamValue::Int(v)) => {
                if v < min || v > max {
                    return Err(format!("value {v} is out of range [{min}, {max}]").into());
                }
            }
            (ParamKind::Choice(names), ParamValue::Choice(c)) => {
                if !names.contains(&c.as_str()) {
                    return Err(format!("\"{c}\" is not one of {}", quote_list(names)).into());
                }
            }
            (ParamKind::Color, ParamValue::Color(c)) => {
                if c.iter().any(|x| !x.is_finite() || *x < 0.0 || *x > 1.0) {
                    return Err(format!("colour {c:?} has a channel outside [0, 1]").into());
                }
            }
            (ParamKind::Vec3, ParamValue::Vec3(v)) => {
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(format!("vector {v:?} is not finite").into());
                }
            }
            (ParamKind::Float { .. }, ParamValue::Relative(r, _)) if self.relative => r.check()?,
            (ParamKind::Bool, ParamValue::Bool(_))
            | (ParamKind::Path, ParamValue::Path(_))
            | (ParamKind::Text, ParamValue::Text(_)) => {}
            (kind, v) => return Err(format!("expected {}, found {}", kind.describe(), v).into()),
        }
        Ok(())
    }

    /// Parses a value typed on the command line (`--set node.param=value`).
    pub fn parse_cli(&self, text: &str) -> Result<ParamValue, ParamError> {
        let text = text.trim();
        let value = match &self.kind {
            ParamKind::Path => ParamValue::Path(text.to_owned()),
            ParamKind::Text => ParamValue::Text(text.to_owned()),
            ParamKind::Choice(_) => ParamValue::Choice(text.trim_matches('"').to_owned()),
            ParamKind::Float { .. } if self.relative && RelativeValue::parse(text).is_ok() => {
                ParamValue::Relative(RelativeValue::parse(text)?, text.to_owned())
            }
            _ => {
                // Numbers, bools and lists: RON syntax, plus bare comma lists ("1,0,0").
                let wrapped = if text.contains(',') && !text.starts_with(['[', '(']) {
                    format!("[{text}]")
                } else {
                    text.to_owned()
                };
                let unreadable = || format!("cannot read `{text}` as {}", self.kind.describe());
                let raw: ron::Value = ron::from_str(&wrapped).map_err(|_| unreadable())?;
                // Bare words parse as RON unit values; report them as the text typed.
                if matches!(raw, ron::Value::Unit | ron::Value::Map(_)) {
                    return Err(unreadable().into());
                }
                return self.convert(&raw);
            }
        };
        self.check(&value)?;
        Ok(value)
    }
}

/// A typed parameter value.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    Float(f64),
    Int(i64),
    Bool(bool),
    Choice(String),
    Color([f64; 4]),
    Vec3([f64; 3]),
    Path(String),
    Text(String),
    /// A data value relative to the connected volume (floats marked [`ParamSpec::relative`]),
    /// with its text as written (saved as it was: `"range(80/255)"` stays so).
    Relative(RelativeValue, String),
}

/// A data value given relative to a volume's values, resolved when the node runs (Issue 25):
/// written in graph files and on the command line as `"percentile(60)"` (of the finite
/// values), `"range(0.3)"` (min + 0.3·(max − min); the argument may be a fraction such as
/// `80/255`) or `"otsu"` (Otsu's threshold between the two classes of the value histogram).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RelativeValue {
    Percentile(f64),
    Range(f64),
    Otsu,
}

impl RelativeValue {
    /// Parses `percentile(P)`, `range(F)` or `otsu` (case and spaces ignored).
    ///
    /// ```
    /// use hatchery_graph::RelativeValue;
    /// assert_eq!(RelativeValue::parse("Percentile( 95 )"), Ok(RelativeValue::Percentile(95.0)));
    /// assert_eq!(RelativeValue::parse("otsu"), Ok(RelativeValue::Otsu));
    /// assert!(RelativeValue::parse("median").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<RelativeValue, ParamError> {
        let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
        let t = t.to_ascii_lowercase();
        if t == "otsu" {
            return Ok(RelativeValue::Otsu);
        }
        let arg = |name: &str| {
            t.strip_prefix(name)
                .and_then(|r| r.strip_prefix('('))
                .and_then(|r| r.strip_suffix(')'))
                .map(|n| {
                    // A number, or a fraction `a/b` ("range(80/255)": 80 of a 0–255 range).
                    let number = |s: &str| s.parse::<f64>().ok().filter(|x| x.is_finite());
                    match n.split_once('/') {
                        Some((a, b)) => number(a).zip(number(b)).map(|(a, b)| a / b),
                        None => number(n),
                    }
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| format!("`{n}` in `{text}` is not a number"))
                })
        };
        let value = if let Some(p) = arg("percentile") {
            RelativeValue::Percentile(p?)
        } else if let Some(f) = arg("range") {
            RelativeValue::Range(f?)
        } else {
            return Err(format!("`{text}` is not percentile(P), range(F) or otsu").into());
        };
        value.check()?;
        Ok(value)
    }

    /// Percentiles lie in [0, 100]; range fractions are finite (outside [0, 1] is beyond the
    /// data's range, allowed).
    pub fn check(&self) -> Result<(), ParamError> {
        match *self {
            RelativeValue::Percentile(p) if !(0.0..=100.0).contains(&p) => {
                Err(format!("percentile {p} is outside [0, 100]").into())
            }
            RelativeValue::Range(f) if !f.is_finite() => {
                Err(format!("range fraction {f} is not finite").into())
            }
            _ => Ok(()),
        }
    }
}

impl fmt::Display for RelativeValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RelativeValue::Percentile(p) => write!(f, "percentile({p})"),
            RelativeValue::Range(x) => write!(f, "range({x})"),
            RelativeValue::Otsu => write!(f, "otsu"),
        }
    }
}

impl ParamValue {
    /// A relative data value written in its canonical form.
    pub fn relative(r: RelativeValue) -> ParamValue {
        ParamValue::Relative(r, r.to_string())
    }

    /// The raw RON value written to a graph file.
    pub fn to_ron(&self) -> ron::Value {
        let num = |x: f64| ron::Value::Number(ron::Number::new(x));
        match self {
            ParamValue::Float(x) => num(*x),
            ParamValue::Int(i) => ron::Value::Number(ron::Number::new(*i)),
            ParamValue::Bool(b) => ron::Value::Bool(*b),
            ParamValue::Choice(s) | ParamValue::Path(s) | ParamValue::Text(s) => {
                ron::Value::String(s.clone())
            }
            ParamValue::Color(c) => ron::Value::Seq(c.iter().map(|x| num(*x)).collect()),
            ParamValue::Vec3(v) => ron::Value::Seq(v.iter().map(|x| num(*x)).collect()),
            ParamValue::Relative(_, text) => ron::Value::String(text.clone()),
        }
    }
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Float(x) => write!(f, "{x}"),
            ParamValue::Int(i) => write!(f, "{i}"),
            ParamValue::Bool(b) => write!(f, "{b}"),
            ParamValue::Choice(s) | ParamValue::Path(s) | ParamValue::Text(s) => {
                write!(f, "\"{s}\"")
            }
            ParamValue::Color(c) => write!(f, "[{}, {}, {}, {}]", c[0], c[1], c[2], c[3]),
            ParamValue::Vec3(v) => write!(f, "[{}, {}, {}]", v[0], v[1], v[2]),
            ParamValue::Relative(_, text) => write!(f, "{text}"),
        }
    }
}

impl Hash for ParamValue {
    fn hash<H: Hasher>(&self, state: &mut H) {
        std::mem::discriminant(self).hash(state);
        match self {
            ParamValue::Float(x) => x.to_bits().hash(state),
            ParamValue::Int(i) => i.hash(state),
            ParamValue::Bool(b) => b.hash(state),
            ParamValue::Choice(s) | ParamValue::Path(s) | ParamValue::Text(s) => s.hash(state),
            ParamValue::Color(c) => c.iter().for_each(|x| x.to_bits().hash(state)),
            ParamValue::Vec3(v) => v.iter().for_each(|x| x.to_bits().hash(state)),
            ParamValue::Relative(_, text) => text.hash(state),
        }
    }
}

fn as_f64(raw: &ron::Value) -> Option<f64> {
    match raw {
        ron::Value::Number(n) => Some(n.into_f64()),
        _ => None,
    }
}

fn as_i64(raw: &ron::Value) -> Option<i64> {
    match raw {
        ron::Value::Number(n) => {
            let f = n.into_f64();
            // Integers only; 3.0 is accepted, 3.5 is not.
            (f.fract() == 0.0 && f.abs() < 9.0e15).then_some(f as i64)
        }
        _ => None,
    }
}

fn as_str(raw: &ron::Value) -> Option<&str> {
    match raw {
        ron::Value::String(s) => Some(s),
        _ => None,
    }
}

fn as_floats(raw: &ron::Value) -> Option<Vec<f64>> {
    match raw {
        ron::Value::Seq(items) => items.iter().map(as_f64).collect(),
        _ => None,
    }
}

fn describe_raw(raw: &ron::Value) -> String {
    match raw {
        ron::Value::Bool(b) => format!("{b}"),
        ron::Value::Number(n) => format!("{}", n.into_f64()),
        ron::Value::String(s) => format!("the string \"{s}\""),
        ron::Value::Seq(items) => format!("a list of {} items", items.len()),
        ron::Value::Map(_) => "a map".into(),
        ron::Value::Option(_) => "an option".into(),
        ron::Value::Char(c) => format!("the character '{c}'"),
        ron::Value::Bytes(_) => "bytes".into(),
        ron::Value::Unit => "()".into(),
    }
}

/// The validated parameters of one node instance, as handed to `execute`.
#[derive(Clone, Debug, Default)]
pub struct Params {
    values: BTreeMap<String, ParamValue>,
    /// Folder that relative paths are resolved against (the graph file's folder).
    base_dir: Option<Arc<Path>>,
}

impl Params {
    pub fn new(values: BTreeMap<String, ParamValue>, base_dir: Option<Arc<Path>>) -> Self {
        Self { values, base_dir }
    }

    pub fn values(&self) -> &BTreeMap<String, ParamValue> {
        &self.values
    }

    pub fn get(&self, name: &str) -> Option<&ParamValue> {
        self.values.get(name)
    }

    pub(crate) fn set(&mut self, name: &str, value: ParamValue) {
        self.values.insert(name.to_owned(), value);
    }

    pub fn base_dir(&self) -> Option<&Path> {
        self.base_dir.as_deref()
    }

    // The typed getters below are called by node code with names from its own schema, whose
    // values the loader has already checked; a miss is a bug in that node, not bad user input.
    fn expect(&self, name: &str) -> &ParamValue {
        self.values.get(name).unwrap_or_else(|| {
            panic!("node code asked for parameter `{name}` missing from its schema")
        })
    }

    pub fn float(&self, name: &str) -> f64 {
        match self.expect(name) {
            ParamValue::Float(x) => *x,
            ParamValue::Int(i) => *i as f64,
            other => panic!("parameter `{name}` is {other}, not a float"),
        }
    }
    pub fn f32(&self, name: &str) -> f32 {
        self.float(name) as f32
    }
    /// A data-value parameter ([`ParamSpec::relative`]): its number, or how it is given
    /// relative to the data (the node resolves it against its volume).
    pub fn data_value(&self, name: &str) -> Result<f64, RelativeValue> {
        match self.expect(name) {
            ParamValue::Relative(r, _) => Err(*r),
            _ => Ok(self.float(name)),
        }
    }
    pub fn int(&self, name: &str) -> i64 {
        match self.expect(name) {
            ParamValue::Int(i) => *i,
            other => panic!("parameter `{name}` is {other}, not an int"),
        }
    }
    pub fn bool(&self, name: &str) -> bool {
        match self.expect(name) {
            ParamValue::Bool(b) => *b,
            other => panic!("parameter `{name}` is {other}, not a bool"),
        }
    }
    pub fn choice(&self, name: &str) -> &str {
        match self.expect(name) {
            ParamValue::Choice(s) => s,
            other => panic!("parameter `{name}` is {other}, not a choice"),
        }
    }
    pub fn color(&self, name: &str) -> [f32; 4] {
        match self.expect(name) {
            ParamValue::Color(c) => c.map(|x| x as f32),
            other => panic!("parameter `{name}` is {other}, not a colour"),
        }
    }
    pub fn vec3(&self, name: &str) -> [f32; 3] {
        match self.expect(name) {
            ParamValue::Vec3(v) => v.map(|x| x as f32),
            other => panic!("parameter `{name}` is {other}, not a vector"),
        }
    }
    pub fn text(&self, name: &str) -> &str {
        match self.expect(name) {
            ParamValue::Text(s) | ParamValue::Path(s) => s,
            other => panic!("parameter `{name}` is {other}, not text"),
        }
    }
    /// A path parameter resolved against the graph file's folder. Empty stays empty.
    pub fn path(&self, name: &str) -> PathBuf {
        let raw = self.text(name);
        let path = PathBuf::from(raw);
        match &self.base_dir {
            Some(base) if !raw.is_empty() && path.is_relative() => base.join(path),
            _ => path,
        }
    }
}

#[cfg(test)]
mod relative_tests {
    use super::*;

    #[test]
    fn relative_values_parse_check_and_print() {
        assert_eq!(
            RelativeValue::parse(" Percentile( 60 )"),
            Ok(RelativeValue::Percentile(60.0))
        );
        assert_eq!(
            RelativeValue::parse("range(80/255)"),
            Ok(RelativeValue::Range(80.0 / 255.0))
        );
        assert_eq!(RelativeValue::parse("OTSU"), Ok(RelativeValue::Otsu));
        assert!(
            RelativeValue::parse("percentile(101)")
                .unwrap_err()
                .to_string()
                .contains("[0, 100]")
        );
        assert!(RelativeValue::parse("range(1/0)").is_err());
        assert!(RelativeValue::parse("median").is_err());
        assert_eq!(
            RelativeValue::Percentile(60.0).to_string(),
            "percentile(60)"
        );
        // Only parameters marked relative take them, from files and the command line.
        let iso = ParamSpec::float("iso", 0.0, -1e12, 1e12, "iso").relative();
        let raw = ron::Value::String("otsu".into());
        assert_eq!(
            iso.convert(&raw),
            Ok(ParamValue::relative(RelativeValue::Otsu))
        );
        assert_eq!(
            iso.parse_cli("range(0.5)"),
            Ok(ParamValue::relative(RelativeValue::Range(0.5)))
        );
        assert_eq!(iso.parse_cli("12.5"), Ok(ParamValue::Float(12.5)));
        let e = iso
            .convert(&ron::Value::String("percentile(x)".into()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a number"), "{e}");
        let plain = ParamSpec::float("step", 0.5, 0.0, 8.0, "step");
        assert!(plain.convert(&raw).is_err());
        assert!(plain.parse_cli("otsu").is_err());
    }
}
