//! What a custom shader declares, read with naga: its bindings become typed input ports, the
//! members of its uniform struct become parameters, its fragment result the output port.
//!
//! The rules (docs/custom_shader.md):
//! - `var NAME: texture_2d<f32>` → input `NAME`: an `Image`, or a `Mask` when NAME is `mask` or
//!   ends in `_mask`.
//! - `var NAME: texture_depth_2d` → input `NAME`: a `GBuffer`, bound as its depth;
//!   `var NAME_normal: texture_2d<f32>` then gets the same G-buffer's normals (xyz, coverage w).
//! - `var NAME: sampler` → a linear, clamp-to-edge sampler.
//! - `var<uniform> NAME: S` (one at most) → a parameter per member of struct `S`: `f32` a float,
//!   `i32`/`u32` an integer, `vec3<f32>` a vector, `vec4<f32>` a colour. A trailing comment on
//!   the member's line may give `default = …`, `range = min..max` and a description.
//! - The one `@fragment` entry point returns `vec4<f32>` (output `image`, premultiplied RGBA) or
//!   `f32` (output `mask`); it may take `@builtin(position)` and `@location(0) uv: vec2<f32>`.
//!
//! Every problem is reported as `file:line:col: message`.
//!
//! Over 600 lines: the whole reflection of a user's shader (bindings → ports, uniform members →
//! parameters, every refusal with its message) in one place, so what a custom shader may declare
//! is read in one file.

use hatchery_graph::{NodeSchema, ParamSpec, PortSpec, PortType, intern};
use naga::{AddressSpace, ImageClass, ScalarKind, TypeInner, VectorSize};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;
use std::sync::Arc;

/// What one binding (all in group 0) is bound to.
#[derive(Clone, Debug, PartialEq)]
pub enum Resource {
    /// An `Image` or `Mask` input's texture.
    Texture {
        port: &'static str,
    },
    /// A `GBuffer` input's depth (Depth32Float).
    Depth {
        port: &'static str,
    },
    /// A `GBuffer` input's normals (Rgba16Float).
    Normal {
        port: &'static str,
    },
    Sampler,
    /// The parameters' uniform buffer.
    Uniform,
}

/// How a uniform member is written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MemberType {
    F32,
    I32,
    U32,
    Vec3,
    Vec4,
}

/// One uniform member: the parameter of the same name, written at `offset` bytes.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub name: &'static str,
    pub offset: u32,
    pub ty: MemberType,
}

/// The uniform struct: `size` bytes, its members.
#[derive(Clone, Debug, PartialEq)]
pub struct Uniform {
    pub size: u32,
    pub members: Vec<Member>,
}

/// A readable, valid custom shader and what it declares.
#[derive(Debug)]
pub struct Reflection {
    pub source: Arc<str>,
    /// Hash of the path and the source: changes when the file's content does.
    pub fingerprint: u64,
    pub entry_point: String,
    pub bindings: Vec<(u32, Resource)>,
    pub uniform: Option<Uniform>,
    /// The output port's type: `Image` (vec4 result) or `Mask` (f32 result).
    pub output: PortType,
    /// The input ports that are masks (R32Float: bound unfilterable).
    pub mask_ports: Vec<&'static str>,
    pub schema: Arc<NodeSchema>,
}

/// Reads `source` (the text of `path`) with naga. `base` is the kind's schema (its `shader`
/// parameter comes first in every instance). Errors are `path:line:col: message`.
pub(crate) fn reflect(path: &Path, source: &str, base: &NodeSchema) -> Result<Reflection, String> {
    // Editors on Windows start files with a byte-order mark; WGSL does not allow one.
    let source = source.strip_prefix('\u{feff}').unwrap_or(source);
    let shown = path.display().to_string();
    let at = |offset: Option<naga::SourceLocation>, message: &str| match offset {
        Some(l) => {
            let (line, column) = line_column(source, l.offset as usize);
            format!("{shown}:{line}:{column}: {message}")
        }
        None => format!("{shown}: {message}"),
    };
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| at(e.location(source), &parse_message(&e)))?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| at(e.location(source), &validation_message(&e)))?;

    let span_at = |span: naga::Span| span.is_defined().then(|| span.location(source));
    let offset_at =
        |offset: usize| Some(naga::Span::new(offset as u32, offset as u32 + 1).location(source));

    // The fragment entry point and its output.
    let fragments: Vec<&naga::EntryPoint> = module
        .entry_points
        .iter()
        .filter(|e| e.stage == naga::ShaderStage::Fragment)
        .collect();
    let [entry] = fragments[..] else {
        return Err(at(
            None,
            &format!(
                "a custom shader has exactly one @fragment entry point; this file has {}",
                fragments.len()
            ),
        ));
    };
    let entry_at = |message: &str| at(find_fn(source, &entry.name).and_then(offset_at), message);
    let output = match entry
        .function
        .result
        .as_ref()
        .map(|r| &module.types[r.ty].inner)
    {
        Some(TypeInner::Vector {
            size: VectorSize::Quad,
            scalar,
        }) if scalar.kind == ScalarKind::Float && scalar.width == 4 => PortType::Image,
        Some(TypeInner::Scalar(scalar))
            if scalar.kind == ScalarKind::Float && scalar.width == 4 =>
        {
            PortType::Mask
        }
        _ => {
            return Err(entry_at(&format!(
                "fragment entry point `{}` must return @location(0) vec4<f32> (an image) or f32 (a mask)",
                entry.name
            )));
        }
    };
    check_fragment_inputs(&module, entry).map_err(|m| entry_at(&m))?;

    // Bindings: textures → ports, samplers, the uniform → parameters.
    let mut bindings = Vec::new();
    let mut inputs = Vec::new();
    let mut uniform = None;
    let mut params = base.params.clone();
    let depth_names: Vec<&str> = module
        .global_variables
        .iter()
        .filter(|(_, g)| {
            matches!(
                module.types[g.ty].inner,
                TypeInner::Image {
                    class: ImageClass::Depth { multi: false },
                    ..
                }
            )
        })
        .filter_map(|(_, g)| g.name.as_deref())
        .collect();
    for (handle, global) in module.global_variables.iter() {
        let Some(binding) = &global.binding else {
            continue;
        };
        let name = global.name.clone().unwrap_or_default();
        let here =
            |message: String| at(span_at(module.global_variables.get_span(handle)), &message);
        if binding.group != 0 {
            return Err(here(format!(
                "`{name}` is in @group({}); a custom shader binds everything in @group(0)",
                binding.group
            )));
        }
        let inner = &module.types[global.ty].inner;
        let resource = match (global.space, inner) {
            (
                AddressSpace::Handle,
                TypeInner::Image {
                    dim: naga::ImageDimension::D2,
                    arrayed: false,
                    class:
                        ImageClass::Sampled {
                            kind: ScalarKind::Float,
                            multi: false,
                        },
                },
            ) => {
                let gbuffer = name
                    .strip_suffix("_normal")
                    .filter(|base| depth_names.contains(base));
                match gbuffer {
                    Some(base) => Resource::Normal { port: intern(base) },
                    None => {
                        let mask = name == "mask" || name.ends_with("_mask");
                        let ty = if mask {
                            PortType::Mask
                        } else {
                            PortType::Image
                        };
                        let doc = if mask {
                            "a mask (one channel, `.r`)"
                        } else {
                            "an image (premultiplied RGBA)"
                        };
                        inputs.push(PortSpec::input(intern(&name), ty, doc));
                        Resource::Texture {
                            port: intern(&name),
                        }
                    }
                }
            }
            (
                AddressSpace::Handle,
                TypeInner::Image {
                    dim: naga::ImageDimension::D2,
                    arrayed: false,
                    class: ImageClass::Depth { multi: false },
                },
            ) => {
                inputs.push(PortSpec::input(
                    intern(&name),
                    PortType::GBuffer,
                    "a G-buffer: its depth here (window-space, 1 where empty); its normals in `<name>_normal` if declared",
                ));
                Resource::Depth {
                    port: intern(&name),
                }
            }
            (AddressSpace::Handle, TypeInner::Sampler { comparison: false }) => Resource::Sampler,
            (AddressSpace::Uniform, TypeInner::Struct { members, span }) => {
                if uniform.is_some() {
                    return Err(here("a custom shader has at most one var<uniform>".into()));
                }
                let struct_span = module.types.get_span(global.ty);
                let mut layout = Uniform {
                    size: *span,
                    members: Vec::new(),
                };
                for m in members {
                    let member = m.name.clone().unwrap_or_default();
                    let found = member_line(source, struct_span, &member);
                    let line = found.map(|(_, at)| at);
                    let comment = found.map_or("", |(o, _)| trailing_comment(&source[o..]));
                    let names: Vec<&str> =
                        members.iter().filter_map(|m| m.name.as_deref()).collect();
                    let on_line = found.map_or(0, |(o, _)| members_on_line(&source[o..], &names));
                    if on_line > 1 && !comment.is_empty() {
                        return Err(at(
                            found.and_then(|(o, _)| offset_at(o)),
                            &format!(
                                "uniform member `{member}` shares its line and comment with another member: put each member on a line of its own"
                            ),
                        ));
                    }
                    let member_at = |message: String| at(line.and_then(offset_at), &message);
                    if params.iter().any(|p| p.name == member) {
                        return Err(member_at(format!(
                            "uniform member `{member}` has the name of the node's own parameter; rename it"
                        )));
                    }
                    let ty = member_type(&module.types[m.ty].inner).ok_or_else(|| {
                        member_at(format!(
                            "uniform member `{member}`: use f32, i32, u32, vec3<f32> or vec4<f32>"
                        ))
                    })?;
                    params.push(param_spec(&member, ty, comment).map_err(member_at)?);
                    layout.members.push(Member {
                        name: intern(&member),
                        offset: m.offset,
                        ty,
                    });
                }
                uniform = Some(layout);
                Resource::Uniform
            }
            _ => {
                return Err(here(format!(
                    "`{name}`: a custom shader binds texture_2d<f32>, texture_depth_2d, sampler and one var<uniform> struct"
                )));
            }
        };
        bindings.push((binding.binding, resource));
    }
    bindings.sort_by_key(|(b, _)| *b);
    if let Some(w) = bindings.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(at(None, &format!("@binding({}) is used twice", w[0].0)));
    }

    // What would only fail when the pipeline is made: caught here, with a place.
    for (handle, o) in module.overrides.iter() {
        if o.init.is_none() {
            let name = o.name.clone().unwrap_or_default();
            return Err(at(
                span_at(module.overrides.get_span(handle)),
                &format!("override `{name}` needs a value (`override {name}: f32 = 1.0;`)"),
            ));
        }
    }
    let entry_index = module
        .entry_points
        .iter()
        .position(|e| std::ptr::eq(e, entry))
        .unwrap_or(0);
    for key in &info.get_entry_point(entry_index).sampling_set {
        let image = &module.global_variables[key.image];
        let name = image.name.clone().unwrap_or_default();
        let not_filterable = inputs
            .iter()
            .any(|p| p.name == name && matches!(p.ty, PortType::Mask | PortType::GBuffer));
        if not_filterable {
            return Err(at(
                span_at(module.global_variables.get_span(key.image)),
                &format!(
                    "`{name}` is read with a sampler: masks (R32Float) and depth are not filterable on every adapter; read it with textureLoad"
                ),
            ));
        }
    }

    let mut hasher = DefaultHasher::new();
    path.hash(&mut hasher);
    source.hash(&mut hasher);
    let output_port = match output {
        PortType::Mask => PortSpec::output("mask", PortType::Mask, "the shader's result"),
        _ => PortSpec::output("image", PortType::Image, "the shader's result"),
    };
    let schema = NodeSchema {
        inputs,
        outputs: vec![output_port],
        params,
        doc: header_doc(source).map_or(base.doc, |d| intern(&d)),
        ..base.clone()
    };
    Ok(Reflection {
        source: Arc::from(source),
        fingerprint: hasher.finish(),
        entry_point: entry.name.clone(),
        bindings,
        uniform,
        output,
        mask_ports: schema
            .inputs
            .iter()
            .filter(|p| p.ty == PortType::Mask)
            .map(|p| p.name)
            .collect(),
        schema: Arc::new(schema),
    })
}

fn parse_message(e: &naga::front::wgsl::ParseError) -> String {
    // The first label usually says what was expected where; the message says what went wrong.
    match e.labels().next() {
        Some((_, label)) if !label.is_empty() && !e.message().contains(label) => {
            format!("{} ({label})", e.message())
        }
        _ => e.message().to_owned(),
    }
}

fn validation_message(e: &naga::WithSpan<naga::valid::ValidationError>) -> String {
    use std::error::Error;
    // naga nests the cause: "Function [1] 'fs_main' is invalid" → "... : the actual reason".
    let mut message = e.as_inner().to_string();
    let mut cause = e.as_inner().source();
    while let Some(c) = cause {
        message.push_str(": ");
        message.push_str(&c.to_string());
        cause = c.source();
    }
    message
}

/// The fragment stage gets only what the vertex stage makes (shaders/custom_shader_vertex.wgsl).
fn check_fragment_inputs(module: &naga::Module, entry: &naga::EntryPoint) -> Result<(), String> {
    let mut bindings = Vec::new();
    for arg in &entry.function.arguments {
        match (&arg.binding, &module.types[arg.ty].inner) {
            (Some(b), inner) => bindings.push((b.clone(), inner.clone())),
            (None, TypeInner::Struct { members, .. }) => {
                for m in members {
                    if let Some(b) = &m.binding {
                        bindings.push((b.clone(), module.types[m.ty].inner.clone()));
                    }
                }
            }
            _ => {}
        }
    }
    for (binding, inner) in bindings {
        let ok = match binding {
            naga::Binding::BuiltIn(naga::BuiltIn::Position { .. }) => true,
            naga::Binding::BuiltIn(_) => true,
            naga::Binding::Location {
                location: 0,
                interpolation,
                sampling,
                ..
            } => {
                // The vertex stage writes uv perspective-correct, sampled at pixel centres.
                let default_interpolation =
                    matches!(interpolation, None | Some(naga::Interpolation::Perspective))
                        && matches!(sampling, None | Some(naga::Sampling::Center));
                default_interpolation
                    && matches!(
                        inner,
                        TypeInner::Vector {
                            size: VectorSize::Bi,
                            scalar
                        } if scalar.kind == ScalarKind::Float && scalar.width == 4
                    )
            }
            naga::Binding::Location { .. } => false,
        };
        if !ok {
            return Err(
                "the fragment stage gets @builtin(position) and @location(0) uv: vec2<f32> (no @interpolate) only"
                    .into(),
            );
        }
    }
    Ok(())
}

fn member_type(inner: &TypeInner) -> Option<MemberType> {
    let f32_ = |s: &naga::Scalar| s.kind == ScalarKind::Float && s.width == 4;
    Some(match inner {
        TypeInner::Scalar(s) if f32_(s) => MemberType::F32,
        TypeInner::Scalar(s) if s.kind == ScalarKind::Sint && s.width == 4 => MemberType::I32,
        TypeInner::Scalar(s) if s.kind == ScalarKind::Uint && s.width == 4 => MemberType::U32,
        TypeInner::Vector {
            size: VectorSize::Tri,
            scalar,
        } if f32_(scalar) => MemberType::Vec3,
        TypeInner::Vector {
            size: VectorSize::Quad,
            scalar,
        } if f32_(scalar) => MemberType::Vec4,
        _ => return None,
    })
}

/// Byte offsets of the line declaring `member` inside the struct's span and of the member's
/// name in it.
fn member_line(source: &str, span: naga::Span, member: &str) -> Option<(usize, usize)> {
    let range = span.to_range()?;
    let text = source.get(range.clone())?;
    let mut offset = range.start;
    for line in text.split_inclusive('\n') {
        if let Some(at) = declares(line, member) {
            return Some((offset, offset + at));
        }
        offset += line.len();
    }
    None
}

/// Where the code part of `line` declares `name:` (as a whole word; attributes such as
/// `@align(16)` may come before it).
fn declares(line: &str, name: &str) -> Option<usize> {
    let code = line.split("//").next().unwrap_or("");
    let mut from = 0;
    while let Some(i) = code[from..].find(name).map(|i| i + from) {
        let before = code[..i].chars().next_back();
        let after = code[i + name.len()..].trim_start();
        let word_start = before.is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        if word_start && after.starts_with(':') {
            return Some(i);
        }
        from = i + name.len();
    }
    None
}

/// How many of `names` the line starting at the text's beginning declares.
fn members_on_line(text: &str, names: &[&str]) -> usize {
    let line = text.lines().next().unwrap_or("");
    names.iter().filter(|n| declares(line, n).is_some()).count()
}

/// The byte offset of `fn NAME(` (a declaration, not in a comment).
fn find_fn(source: &str, name: &str) -> Option<usize> {
    let mut offset = 0;
    for line in source.split_inclusive('\n') {
        let code = line.split("//").next().unwrap_or("");
        let mut from = 0;
        while let Some(i) = code[from..].find("fn").map(|i| i + from) {
            let rest = code[i + 2..].trim_start();
            let boundary = code[..i]
                .chars()
                .next_back()
                .is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
            if boundary
                && let Some(after) = rest.strip_prefix(name)
                && after.trim_start().starts_with('(')
            {
                return Some(offset + i);
            }
            from = i + 2;
        }
        offset += line.len();
    }
    None
}

/// 1-based line and column (in characters) of byte `offset`.
fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let before = &source[..offset.min(source.len())];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

/// The `// …` comment at the end of the line starting at the text's beginning.
fn trailing_comment(text: &str) -> &str {
    let line = text.lines().next().unwrap_or("");
    line.find("//").map_or("", |i| line[i + 2..].trim())
}

/// The parameter for a uniform member, from its type and its comment:
/// `default = 0.5, range = 0..1, what it does`.
fn param_spec(name: &str, ty: MemberType, comment: &str) -> Result<ParamSpec, String> {
    let fail = |message: String| format!("uniform member `{name}`: {message}");
    let mut default: Option<ron::Value> = None;
    let mut range: Option<(f64, f64)> = None;
    let mut doc = Vec::new();
    for part in split_top_level(comment) {
        let part = part.trim();
        if let Some(v) = part.strip_prefix("default").map(str::trim_start)
            && let Some(v) = v.strip_prefix('=')
        {
            if default.is_some() {
                return Err(fail("`default` is given twice".into()));
            }
            default = Some(ron::from_str(v.trim()).map_err(|_| {
                fail(format!(
                    "`default = {}` is not a number or a list of numbers",
                    v.trim()
                ))
            })?);
        } else if let Some(v) = part.strip_prefix("range").map(str::trim_start)
            && let Some(v) = v.strip_prefix('=')
        {
            if range.is_some() {
                return Err(fail("`range` is given twice".into()));
            }
            let bad = || fail("write the range as `range = min..max` (finite, min < max)".into());
            let (lo, hi) = v.trim().split_once("..").ok_or_else(bad)?;
            let (lo, hi) = (lo.trim().parse::<f64>(), hi.trim().parse::<f64>());
            match (lo, hi) {
                (Ok(lo), Ok(hi)) if lo < hi && lo.is_finite() && hi.is_finite() => {
                    range = Some((lo, hi))
                }
                _ => return Err(bad()),
            }
        } else if !part.is_empty() {
            doc.push(part);
        }
    }
    let doc = intern(&doc.join(", "));
    let name = intern(name);
    let spec = match ty {
        MemberType::F32 => {
            let (min, max) = range.unwrap_or((0.0, 1.0));
            ParamSpec::float(name, min, min, max, doc)
        }
        MemberType::I32 | MemberType::U32 => {
            let (floor, ceiling, what) = match ty {
                MemberType::U32 => (0.0, u32::MAX as f64, "a u32 holds 0 to 4294967295"),
                _ => (
                    i32::MIN as f64,
                    i32::MAX as f64,
                    "an i32 holds -2147483648 to 2147483647",
                ),
            };
            let (min, max) = range.unwrap_or((0.0, 100.0));
            if min < floor || max > ceiling {
                return Err(fail(format!("range {min}..{max}: {what}")));
            }
            if min.fract() != 0.0 || max.fract() != 0.0 {
                return Err(fail(format!(
                    "range {min}..{max}: use whole numbers for an integer"
                )));
            }
            ParamSpec::int(name, min as i64, min as i64, max as i64, doc)
        }
        MemberType::Vec3 | MemberType::Vec4 if range.is_some() => {
            return Err(fail(
                "`range` applies to numbers, not to vectors and colours".into(),
            ));
        }
        MemberType::Vec3 => ParamSpec::vec3(name, [0.0; 3], doc),
        MemberType::Vec4 => ParamSpec::color(name, [0.0, 0.0, 0.0, 1.0], doc),
    };
    let Some(raw) = default else {
        return Ok(spec);
    };
    let value = spec
        .convert(&raw)
        .map_err(|m| fail(format!("default: {m}")))?;
    Ok(ParamSpec {
        default: value,
        ..spec
    })
}

/// Splits at commas outside brackets (`default = [1, 0, 0, 1], the colour`).
fn split_top_level(text: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '[' | '(' => depth += 1,
            // A stray `)` in a description (a smiley) does not open a bracket.
            ']' | ')' => depth = (depth - 1).max(0),
            ',' if depth == 0 => {
                parts.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&text[start..]);
    parts
}

/// The file's leading `//` comment block, as one paragraph (the node's description).
fn header_doc(source: &str) -> Option<String> {
    let lines: Vec<&str> = source
        .lines()
        .map(str::trim)
        .take_while(|l| l.starts_with("//"))
        .map(|l| l.trim_start_matches('/').trim())
        .collect();
    let doc = lines.join(" ").trim().to_owned();
    (!doc.is_empty()).then_some(doc)
}
