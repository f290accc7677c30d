//! Node parameters declared once (issue 29): a struct per node kind whose fields carry name,
//! type, default, range and doc. [`node_params!`](crate::node_params) generates the kind's
//! [`ParamSpec`]s from it and reads a node's validated [`Params`] into it, so node code reads
//! `params.depth_threshold` and a misspelt name fails to compile instead of panicking.
//!
//! A declarative macro rather than a derive: it needs no proc-macro crate (syn, quote) in the
//! tree, and what it generates — a `specs()` list and a `read()` — is short enough to follow.

use crate::ParamError;
use crate::param::{ParamSpec, ParamValue, Params, RelativeValue};
use crate::schema::intern;
use std::path::PathBuf;

/// A Rust type a parameter field may have, and how it maps to a [`ParamSpec`]:
/// `f32`/`f64` → float (a range is required), `i64`/`u32` → int (range required), `bool`,
/// `[f32; 4]` → colour, `[f32; 3]` → vec3, `PathBuf` → path (resolved against the graph file's
/// folder), `String` → text, [`DataValue`] → a float that may be relative to the data, and an
/// enum declared with [`param_choice!`](crate::param_choice) → choice.
pub trait ParamField: Sized {
    /// The type of the default as written in the declaration.
    type Default;
    /// The spec of a field `name` with `default`, `range` (`[min, max]`, numbers only) and
    /// one-line `doc`. Panics when a number has no range: a declaration bug, caught by every
    /// test that builds the registry.
    fn specs(
        name: &'static str,
        default: Self::Default,
        range: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec>;
    /// The field's value in `params` (validated against the same spec by the loader).
    /// Errors only when `params` did not come from this spec (a bug): the message names it.
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError>;
}

fn range_of(name: &str, range: Option<[f64; 2]>) -> [f64; 2] {
    range.unwrap_or_else(|| panic!("number parameter `{name}` is declared without a range"))
}

fn value<'a>(params: &'a Params, name: &str) -> Result<&'a ParamValue, ParamError> {
    params.get(name).ok_or_else(|| {
        ParamError(format!(
            "parameter `{name}` is missing from the node's values"
        ))
    })
}

impl ParamField for f64 {
    type Default = f64;
    fn specs(name: &'static str, d: f64, r: Option<[f64; 2]>, doc: &'static str) -> Vec<ParamSpec> {
        let [min, max] = range_of(name, r);
        vec![ParamSpec::float(name, d, min, max, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Float(x) => Ok(*x),
            ParamValue::Int(i) => Ok(*i as f64),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not a number"
            ))),
        }
    }
}

impl ParamField for f32 {
    type Default = f64;
    fn specs(name: &'static str, d: f64, r: Option<[f64; 2]>, doc: &'static str) -> Vec<ParamSpec> {
        f64::specs(name, d, r, doc)
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        f64::read(params, name).map(|x| x as f32)
    }
}

impl ParamField for i64 {
    type Default = i64;
    fn specs(name: &'static str, d: i64, r: Option<[f64; 2]>, doc: &'static str) -> Vec<ParamSpec> {
        let [min, max] = range_of(name, r);
        vec![ParamSpec::int(name, d, min as i64, max as i64, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Int(i) => Ok(*i),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not an integer"
            ))),
        }
    }
}

impl ParamField for u32 {
    type Default = i64;
    fn specs(name: &'static str, d: i64, r: Option<[f64; 2]>, doc: &'static str) -> Vec<ParamSpec> {
        let [min, max] = range_of(name, r);
        assert!(
            min >= 0.0 && max <= u32::MAX as f64,
            "`{name}`: range beyond u32"
        );
        i64::specs(name, d, r, doc)
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        let i = i64::read(params, name)?;
        u32::try_from(i)
            .map_err(|_| ParamError(format!("parameter `{name}` = {i} does not fit u32")))
    }
}

impl ParamField for bool {
    type Default = bool;
    fn specs(
        name: &'static str,
        d: bool,
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::bool(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Bool(b) => Ok(*b),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not true or false"
            ))),
        }
    }
}

/// RGBA, channels in [0, 1].
impl ParamField for [f32; 4] {
    type Default = [f64; 4];
    fn specs(
        name: &'static str,
        d: [f64; 4],
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::color(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Color(c) => Ok(c.map(|x| x as f32)),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not a colour"
            ))),
        }
    }
}

impl ParamField for [f32; 3] {
    type Default = [f64; 3];
    fn specs(
        name: &'static str,
        d: [f64; 3],
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::vec3(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Vec3(v) => Ok(v.map(|x| x as f32)),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not a vector"
            ))),
        }
    }
}

/// A file path; relative paths resolve against the graph file's folder, empty stays empty.
impl ParamField for PathBuf {
    type Default = &'static str;
    fn specs(
        name: &'static str,
        d: &'static str,
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::path(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Path(_) | ParamValue::Text(_) => Ok(params.path(name)),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not a path"
            ))),
        }
    }
}

/// A file path as written in the graph file (`written`: the key a loader caches by, the text
/// a user sees) and resolved against the graph file's folder (`resolved`; empty stays empty).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilePath {
    pub written: String,
    pub resolved: PathBuf,
}

impl FilePath {
    /// Whether no file is named (the written text is blank).
    pub fn is_blank(&self) -> bool {
        self.written.trim().is_empty()
    }
}

impl ParamField for FilePath {
    type Default = &'static str;
    fn specs(
        name: &'static str,
        d: &'static str,
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::path(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        Ok(FilePath {
            written: String::read(params, name)?,
            resolved: PathBuf::read(params, name)?,
        })
    }
}

impl ParamField for String {
    type Default = &'static str;
    fn specs(
        name: &'static str,
        d: &'static str,
        _: Option<[f64; 2]>,
        doc: &'static str,
    ) -> Vec<ParamSpec> {
        vec![ParamSpec::text(name, d, doc)]
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Text(s) | ParamValue::Path(s) => Ok(s.clone()),
            other => Err(ParamError(format!(
                "parameter `{name}` is {other}, not text"
            ))),
        }
    }
}

/// A value in the data's units that may be given relative to the connected volume's values
/// (`"percentile(60)"`, `"range(0.3)"`, `"otsu"`; see [`RelativeValue`]): the node resolves a
/// relative one against its volume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DataValue {
    Number(f64),
    Relative(RelativeValue),
}

impl ParamField for DataValue {
    type Default = f64;
    fn specs(name: &'static str, d: f64, r: Option<[f64; 2]>, doc: &'static str) -> Vec<ParamSpec> {
        f64::specs(name, d, r, doc)
            .into_iter()
            .map(ParamSpec::relative)
            .collect()
    }
    fn read(params: &Params, name: &'static str) -> Result<Self, ParamError> {
        match value(params, name)? {
            ParamValue::Relative(r, _) => Ok(DataValue::Relative(*r)),
            _ => f64::read(params, name).map(DataValue::Number),
        }
    }
}

/// The default of a group field: a parameter struct declared with
/// [`node_params!`](crate::node_params) whose parameters several kinds share (the Blinn–Phong
/// coefficients of the ray casters), written `pub phong: PhongParams = Group;`.
#[derive(Clone, Copy, Debug)]
pub struct Group;

/// A field's doc comment lines (`#[doc = " …"]`) as one line of text, stored once.
pub fn doc_text(lines: &[&str]) -> &'static str {
    let words: Vec<&str> = lines.iter().flat_map(|l| l.split_whitespace()).collect();
    intern(&words.join(" "))
}

/// Declares a node kind's parameters as a struct:
///
/// ```ignore
/// hatchery_graph::node_params! {
///     /// Parameters of `Silhouette`.
///     pub struct SilhouetteParams {
///         /// threshold on the Sobel depth-gradient magnitude
///         pub depth_threshold: f32 = 0.001, range(0.0, 100.0);
///         /// detect depth discontinuities (eq. 3)
///         pub use_depth: bool = true;
///         /// perturbation P(x, y) of the sampling positions
///         pub pip: PipMode = PipMode::None;
///     }
/// }
/// ```
///
/// Each field: doc comment (the parameter's one-line doc), name, [`ParamField`] type, default,
/// then `range(min, max)` for numbers, `unit(pixels)` for a length in pixels of the designed
/// figure (scaled with the render, [`crate::ParamSpec::pixels`]), optionally `reads(InputKind::…)` for a path a graph
/// input may bind and `widget(Widget::…)` for the editor widget it needs. Generates `specs()` (for the kind's schema, in declaration order) and
/// `read(&Params) -> Result<Self, NodeError>`. A field whose type is another such struct, with
/// default [`Group`], puts that struct's parameters in its place.
#[macro_export]
macro_rules! node_params {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $(
                $(#[doc = $doc:expr])*
                $fvis:vis $field:ident : $ty:ty = $default:expr
                    $(, range($min:expr, $max:expr))?
                    $(, unit($unit:ident))?
                    $(, reads($reads:expr))?
                    $(, widget($widget:expr))?
                ;
            )*
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Debug, PartialEq)]
        $vis struct $name {
            $( $(#[doc = $doc])* $fvis $field: $ty, )*
        }

        impl $name {
            /// The parameters' specs, in declaration order (the kind's `NodeSchema::params`).
            #[allow(unused_mut)]
            pub fn specs() -> Vec<$crate::ParamSpec> {
                let mut specs = Vec::new();
                $({
                    let range: Option<[f64; 2]> = None $(.or(Some([$min as f64, $max as f64])))?;
                    let field = <$ty as $crate::node_params::ParamField>::specs(
                        stringify!($field),
                        $default,
                        range,
                        $crate::node_params::doc_text(&[$($doc),*]),
                    );
                    specs.extend(
                        field
                            .into_iter()
                            $(.map(|s| s.$unit()))?
                            $(.map(|s| s.reads($reads)))?
                            $(.map(|s| s.widget($widget)))?,
                    );
                })*
                specs
            }

            /// Reads a node's validated parameters. Errors name a parameter `params` lacks or
            /// holds with another type — possible only for values not checked against
            /// [`Self::specs`].
            pub fn read(params: &$crate::Params) -> Result<Self, $crate::NodeError> {
                Ok(Self {
                    $( $field: <$ty as $crate::node_params::ParamField>::read(params, stringify!($field))
                        .map_err($crate::NodeError::new)?, )*
                })
            }
        }

        /// A parameter struct is itself a field of another: its parameters in place (a group
        /// shared by several kinds, declared `pub name: Group = Group;`).
        impl $crate::node_params::ParamField for $name {
            type Default = $crate::node_params::Group;
            fn specs(
                _: &'static str,
                _: $crate::node_params::Group,
                _: Option<[f64; 2]>,
                _: &'static str,
            ) -> Vec<$crate::ParamSpec> {
                $name::specs()
            }
            fn read(params: &$crate::Params, _: &'static str) -> Result<Self, $crate::ParamError> {
                $name::read(params).map_err(|e| $crate::ParamError(e.message))
            }
        }
    };
}

/// Declares a choice parameter's values as a `#[repr(u32)]` enum (its discriminants are the
/// codes a shader receives), each with the name written in graph files:
///
/// ```ignore
/// hatchery_graph::param_choice! {
///     /// Perturbation P(x, y) of the sampling positions.
///     pub enum PipMode { None = "none", Constant = "constant" }
/// }
/// ```
#[macro_export]
macro_rules! param_choice {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident { $( $(#[$vmeta:meta])* $variant:ident = $text:literal ),+ $(,)? }
    ) => {
        $(#[$meta])*
        #[repr(u32)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $name { $( $(#[$vmeta])* $variant ),+ }

        impl $name {
            /// Every value, in declaration order (the code order).
            pub const ALL: &'static [$name] = &[$($name::$variant),+];
            /// The names written in graph files, in declaration order.
            pub const NAMES: &'static [&'static str] = &[$($text),+];
            /// The name written in graph files.
            pub fn name(self) -> &'static str {
                Self::NAMES[self as usize]
            }
            /// The value written `text` in a graph file.
            pub fn from_name(text: &str) -> Option<Self> {
                Self::NAMES.iter().position(|n| *n == text).map(|i| Self::ALL[i])
            }
        }

        impl $crate::node_params::ParamField for $name {
            type Default = $name;
            fn specs(
                name: &'static str,
                default: $name,
                _: Option<[f64; 2]>,
                doc: &'static str,
            ) -> Vec<$crate::ParamSpec> {
                vec![$crate::ParamSpec::choice(name, default.name(), Self::NAMES, doc)]
            }
            fn read(params: &$crate::Params, name: &'static str) -> Result<Self, $crate::ParamError> {
                match params.get(name) {
                    Some($crate::ParamValue::Choice(c)) => Self::from_name(c).ok_or_else(|| {
                        $crate::ParamError(format!("parameter `{name}`: \"{c}\" is not one of {:?}", Self::NAMES))
                    }),
                    Some(other) => Err($crate::ParamError(format!("parameter `{name}` is {other}, not a choice"))),
                    None => Err($crate::ParamError(format!("parameter `{name}` is missing from the node's values"))),
                }
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use crate::{ParamKind, ParamValue, Params};
    use std::collections::BTreeMap;

    crate::param_choice! {
        /// How to draw.
        pub enum Style { Plain = "plain", Dotted = "dotted" }
    }

    crate::node_params! {
        /// A kind's parameters.
        pub struct Example {
            /// a width
            /// in pixels
            pub width: f32 = 1.5, range(0.0, 8.0);
            /// how many
            pub count: u32 = 3, range(1, 10);
            /// the style
            pub style: Style = Style::Dotted;
            /// a file
            pub file: std::path::PathBuf = "";
            /// an iso value
            pub iso: crate::node_params::DataValue = 0.0, range(-1e12, 1e12);
        }
    }

    crate::node_params! {
        /// Parameters shared by several kinds.
        pub struct Shared {
            /// a gain
            pub gain: f32 = 2.0, range(0.0, 4.0);
        }
    }

    crate::node_params! {
        /// A kind using the shared group between its own parameters.
        pub struct WithGroup {
            /// first
            pub first: bool = true;
            pub shared: Shared = crate::node_params::Group;
            /// a file as written and resolved
            pub file: crate::FilePath = "";
        }
    }

    #[test]
    fn a_group_puts_its_parameters_in_place() {
        let names: Vec<_> = WithGroup::specs().iter().map(|s| s.name).collect();
        assert_eq!(names, ["first", "gain", "file"]);
        let values: BTreeMap<String, ParamValue> = [
            ("first".to_owned(), ParamValue::Bool(false)),
            ("gain".to_owned(), ParamValue::Float(3.0)),
            ("file".to_owned(), ParamValue::Path("data/a.nii".into())),
        ]
        .into();
        let base: std::sync::Arc<std::path::Path> = std::path::Path::new("/g").into();
        let read = WithGroup::read(&Params::new(values, Some(base))).unwrap();
        assert!(!read.first);
        assert_eq!(read.shared.gain, 3.0);
        assert_eq!(read.file.written, "data/a.nii");
        assert_eq!(read.file.resolved, std::path::Path::new("/g/data/a.nii"));
        assert!(!read.file.is_blank());
    }

    #[test]
    fn a_declaration_gives_specs_and_typed_values() {
        let specs = Example::specs();
        let names: Vec<_> = specs.iter().map(|s| s.name).collect();
        assert_eq!(names, ["width", "count", "style", "file", "iso"]);
        assert_eq!(specs[0].doc, "a width in pixels");
        assert_eq!(specs[0].kind, ParamKind::Float { min: 0.0, max: 8.0 });
        assert_eq!(specs[1].kind, ParamKind::Int { min: 1, max: 10 });
        assert_eq!(specs[2].kind, ParamKind::Choice(&["plain", "dotted"]));
        assert_eq!(specs[2].default, ParamValue::Choice("dotted".into()));
        assert!(specs[4].relative && !specs[0].relative);

        let mut values: BTreeMap<String, ParamValue> = specs
            .iter()
            .map(|s| (s.name.to_owned(), s.default.clone()))
            .collect();
        values.insert("style".into(), ParamValue::Choice("plain".into()));
        values.insert("file".into(), ParamValue::Path("a.png".into()));
        let base: std::sync::Arc<std::path::Path> = std::path::Path::new("/graphs").into();
        let read = Example::read(&Params::new(values.clone(), Some(base))).unwrap();
        assert_eq!(read.width, 1.5);
        assert_eq!(read.count, 3);
        assert_eq!(read.style, Style::Plain);
        assert_eq!(read.style as u32, 0);
        assert_eq!(read.file, std::path::Path::new("/graphs/a.png"));
        assert_eq!(read.iso, crate::node_params::DataValue::Number(0.0));

        values.remove("count");
        let e = Example::read(&Params::new(values, None)).unwrap_err();
        assert!(e.message.contains("`count`"), "{e}");
    }
}
