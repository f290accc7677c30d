//! Checks over the workspace's own sources (issue 35): no public library function returns
//! `Result<_, String>`, every declared dependency is used where it is declared, and the library
//! crates without `unsafe` forbid it.
//!
//! The sources are parsed with syn (not matched with regular expressions), so a signature split
//! over lines or a `use` inside a macro is read as the compiler reads it. Test code (`#[cfg(test)]`
//! items, `tests/`) is left out of the API check and counts only for dev-dependencies.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use syn::visit::Visit;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The library crates: what a caller links against. The editor and the command line are
/// applications (their errors end as status lines and `anyhow` reports); the Python extension's
/// errors are Python exceptions.
const LIBRARIES: [&str; 6] = [
    "crates/hatchery-graph",
    "crates/hatchery-gpu",
    "crates/hatchery-data",
    "crates/hatchery-nodes",
    "crates/hatchery-annotation",
    "crates/hatchery-batch",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn parse(path: &Path) -> syn::File {
    let text = std::fs::read_to_string(path).unwrap();
    syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn is_cfg_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("cfg")
            && a.parse_args::<syn::Meta>()
                .is_ok_and(|m| m.path().is_ident("test"))
    })
}

/// `Result<_, String>` (any path ending in `Result`, any path ending in `String`).
fn is_string_result(ty: &syn::Type) -> bool {
    let syn::Type::Path(p) = ty else { return false };
    let Some(last) = p.path.segments.last() else {
        return false;
    };
    if last.ident != "Result" {
        return false;
    }
    let syn::PathArguments::AngleBracketed(args) = &last.arguments else {
        return false;
    };
    let Some(syn::GenericArgument::Type(syn::Type::Path(e))) = args.args.iter().nth(1) else {
        return false;
    };
    e.path.segments.last().is_some_and(|s| s.ident == "String")
}

/// Public functions and methods returning `Result<_, String>`, and public type aliases to one.
struct StringErrors<'a> {
    file: &'a Path,
    found: Vec<String>,
}

impl StringErrors<'_> {
    fn check(&mut self, vis: &syn::Visibility, sig: &syn::Signature) {
        if let (syn::Visibility::Public(_), syn::ReturnType::Type(_, ty)) = (vis, &sig.output)
            && is_string_result(ty)
        {
            self.found
                .push(format!("{}: fn {}", self.file.display(), sig.ident));
        }
    }
}

impl<'ast> Visit<'ast> for StringErrors<'_> {
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if !is_cfg_test(&m.attrs) {
            syn::visit::visit_item_mod(self, m);
        }
    }
    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        if !is_cfg_test(&f.attrs) {
            self.check(&f.vis, &f.sig);
        }
    }
    fn visit_item_impl(&mut self, i: &'ast syn::ItemImpl) {
        // Trait impls have the trait's signatures (FromStr::Err = String would be the trait's
        // choice, and is caught at the trait's declaration when it is ours).
        if i.trait_.is_none() && !is_cfg_test(&i.attrs) {
            syn::visit::visit_item_impl(self, i);
        }
    }
    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.check(&f.vis, &f.sig);
    }
    fn visit_item_trait(&mut self, t: &'ast syn::ItemTrait) {
        if matches!(t.vis, syn::Visibility::Public(_)) {
            for item in &t.items {
                if let syn::TraitItem::Fn(f) = item {
                    self.check(&t.vis, &f.sig);
                }
            }
        }
    }
    fn visit_item_type(&mut self, t: &'ast syn::ItemType) {
        if matches!(t.vis, syn::Visibility::Public(_)) && is_string_result(&t.ty) {
            self.found
                .push(format!("{}: type {}", self.file.display(), t.ident));
        }
    }
}

#[test]
fn no_public_library_function_returns_a_string_error() {
    let mut found = Vec::new();
    let mut read = 0;
    for lib in LIBRARIES {
        let mut files = Vec::new();
        rust_files(&Path::new(ROOT).join(lib).join("src"), &mut files);
        for file in &files {
            let ast = parse(file);
            let mut v = StringErrors {
                file: file.strip_prefix(ROOT).unwrap(),
                found: Vec::new(),
            };
            v.visit_file(&ast);
            found.extend(v.found);
            read += 1;
        }
    }
    assert!(read > 50, "only {read} files read: wrong root?");
    assert!(
        found.is_empty(),
        "public library functions returning Result<_, String> (return the crate's error type):\n{}",
        found.join("\n")
    );
}

/// Every identifier a set of files uses (paths, `use` trees, the tokens inside macros), with or
/// without their `#[cfg(test)]` items.
struct Idents {
    skip_tests: bool,
    found: BTreeSet<String>,
}

impl Idents {
    fn tokens(&mut self, tokens: proc_macro2::TokenStream) {
        for t in tokens {
            match t {
                proc_macro2::TokenTree::Ident(i) => {
                    self.found.insert(i.to_string());
                }
                proc_macro2::TokenTree::Group(g) => self.tokens(g.stream()),
                _ => {}
            }
        }
    }
}

impl<'ast> Visit<'ast> for Idents {
    fn visit_ident(&mut self, i: &'ast proc_macro2::Ident) {
        self.found.insert(i.to_string());
    }
    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        syn::visit::visit_macro(self, m);
        self.tokens(m.tokens.clone());
    }
    fn visit_attribute(&mut self, a: &'ast syn::Attribute) {
        // #[derive(serde::Serialize)], #[pyo3(...)], #[error(...)]: the tokens of attributes.
        if let syn::Meta::List(l) = &a.meta {
            self.tokens(l.tokens.clone());
        }
        syn::visit::visit_attribute(self, a);
    }
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let attrs: &[syn::Attribute] = match item {
            syn::Item::Mod(m) => &m.attrs,
            syn::Item::Fn(f) => &f.attrs,
            syn::Item::Use(u) => &u.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Const(c) => &c.attrs,
            syn::Item::Static(s) => &s.attrs,
            syn::Item::Struct(s) => &s.attrs,
            _ => &[],
        };
        if !(self.skip_tests && is_cfg_test(attrs)) {
            syn::visit::visit_item(self, item);
        }
    }
}

fn idents(files: &[PathBuf], skip_tests: bool) -> BTreeSet<String> {
    let mut v = Idents {
        skip_tests,
        found: BTreeSet::new(),
    };
    for f in files {
        v.visit_file(&parse(f));
    }
    v.found
}

/// `cargo metadata --format-version 1` with `args`, parsed.
fn cargo_metadata(args: &[&str]) -> serde_json::Value {
    let out = std::process::Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1"])
        .args(args)
        .current_dir(ROOT)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "cargo metadata: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The same check as cargo-machete, on `cargo metadata --no-deps` (no network): a normal
/// dependency is used by the package's non-test code (src/, build.rs), a dev-dependency by its
/// tests, examples or benches (or its test modules). A dependency only needed for a feature it
/// turns on is listed in `[package.metadata.cargo-machete] ignored` with a comment saying why,
/// as for cargo-machete.
#[test]
fn every_declared_dependency_is_used() {
    let meta = cargo_metadata(&["--no-deps", "--offline"]);
    let mut unused = Vec::new();
    let mut checked = 0;
    for package in meta["packages"].as_array().unwrap() {
        let name = package["name"].as_str().unwrap();
        let dir = Path::new(package["manifest_path"].as_str().unwrap())
            .parent()
            .unwrap();
        let ignored: BTreeSet<&str> = package["metadata"]["cargo-machete"]["ignored"]
            .as_array()
            .map(|a| a.iter().filter_map(|v| v.as_str()).collect())
            .unwrap_or_default();
        let (mut main, mut test) = (Vec::new(), Vec::new());
        rust_files(&dir.join("src"), &mut main);
        if dir.join("build.rs").exists() {
            main.push(dir.join("build.rs"));
        }
        for d in ["tests", "examples", "benches"] {
            rust_files(&dir.join(d), &mut test);
        }
        let used_by_code = idents(&main, true);
        let mut used_by_tests = idents(&main, false);
        used_by_tests.extend(idents(&test, false));
        for dep in package["dependencies"].as_array().unwrap() {
            let package_name = dep["name"].as_str().unwrap();
            if ignored.contains(package_name) {
                continue;
            }
            // The name code uses: the rename in Cargo.toml, or the package's with `_` for `-`.
            let crate_name = dep["rename"]
                .as_str()
                .unwrap_or(package_name)
                .replace('-', "_");
            let (used, what) = match dep["kind"].as_str() {
                None => (&used_by_code, "dependency"),
                Some("dev") => (&used_by_tests, "dev-dependency"),
                Some(_) => continue, // build-dependencies: none here
            };
            checked += 1;
            if !used.contains(&crate_name) {
                unused.push(format!("{name}: {what} `{package_name}`"));
            }
        }
    }
    assert!(checked > 50, "only {checked} dependencies checked");
    assert!(
        unused.is_empty(),
        "declared but not used (remove them, or move them to where they are used):\n{}",
        unused.join("\n")
    );
}

/// The library crates without `unsafe` say so to the compiler; hatchery-data's one block (the
/// memory map) is allowed where it is, under `deny`.
#[test]
fn library_crates_forbid_unsafe_code() {
    for lib in LIBRARIES {
        let lib_rs = Path::new(ROOT).join(lib).join("src/lib.rs");
        let ast = parse(&lib_rs);
        let level = ast.attrs.iter().find_map(|a| {
            let list = a.meta.require_list().ok()?;
            if list.tokens.to_string() != "unsafe_code" {
                return None;
            }
            list.path.get_ident().map(|i| i.to_string())
        });
        let mut files = Vec::new();
        rust_files(&Path::new(ROOT).join(lib).join("src"), &mut files);
        let mut finder = UnsafeCode(false);
        for f in &files {
            finder.visit_file(&parse(f));
        }
        let has_unsafe = finder.0;
        let want = if has_unsafe { "deny" } else { "forbid" };
        assert_eq!(
            level.as_deref(),
            Some(want),
            "{lib}: #![{want}(unsafe_code)] expected in src/lib.rs"
        );
    }
}

/// Whether any `unsafe` block, function or impl is in the files visited.
struct UnsafeCode(bool);

impl<'ast> Visit<'ast> for UnsafeCode {
    fn visit_expr_unsafe(&mut self, _: &'ast syn::ExprUnsafe) {
        self.0 = true;
    }
    fn visit_signature(&mut self, s: &'ast syn::Signature) {
        self.0 |= s.unsafety.is_some();
    }
    fn visit_item_impl(&mut self, i: &'ast syn::ItemImpl) {
        self.0 |= i.unsafety.is_some();
        syn::visit::visit_item_impl(self, i);
    }
}

/// Whether an SPDX licence expression (`/` read as `OR`, as old crates write it) can be met by
/// MIT or Apache-2.0 style terms alone, which ask only for the licence text to travel along.
fn permissive_alone(expr: &str) -> bool {
    const PERMISSIVE: [&str; 6] = ["MIT", "MIT-0", "Apache-2.0", "Unlicense", "0BSD", "CC0-1.0"];
    let spaced = expr
        .replace('/', " OR ")
        .replace('(', " ( ")
        .replace(')', " ) ");
    let tokens: Vec<&str> = spaced.split_whitespace().collect();
    // Recursive descent: or := and ("OR" and)*; and := atom ("AND" atom)*;
    // atom := "(" or ")" | id ["WITH" exception].
    fn or(t: &[&str], i: &mut usize) -> bool {
        let mut v = and(t, i);
        while t.get(*i) == Some(&"OR") {
            *i += 1;
            v |= and(t, i);
        }
        v
    }
    fn and(t: &[&str], i: &mut usize) -> bool {
        let mut v = atom(t, i);
        while t.get(*i) == Some(&"AND") {
            *i += 1;
            v &= atom(t, i);
        }
        v
    }
    fn atom(t: &[&str], i: &mut usize) -> bool {
        let tok = t.get(*i).copied().unwrap_or("");
        *i += 1;
        if tok == "(" {
            let v = or(t, i);
            *i += 1; // ")"
            return v;
        }
        if t.get(*i) == Some(&"WITH") {
            *i += 2; // an exception only widens what the licence allows
        }
        PERMISSIVE.contains(&tok)
    }
    or(&tokens, &mut 0)
}

#[test]
fn licence_expressions_are_read_as_spdx() {
    assert!(permissive_alone("MIT OR Apache-2.0"));
    assert!(permissive_alone("MIT/Apache-2.0"));
    assert!(permissive_alone("Apache-2.0 OR GPL-2.0-only"));
    assert!(permissive_alone(
        "Apache-2.0 WITH LLVM-exception OR Apache-2.0 OR MIT"
    ));
    assert!(!permissive_alone("(MIT OR Apache-2.0) AND IJG"));
    assert!(!permissive_alone("BSD-3-Clause"));
    assert!(!permissive_alone("MPL-2.0"));
}

/// Every crate in the build whose terms ask for more than MIT or Apache-2.0 (an acknowledgement,
/// a copyright notice, a font licence, MPL source) is named in NOTICE, so a binary release
/// credits it: the IJG clause of jpeg-encoder first of all (issue 35).
#[test]
fn notice_credits_every_dependency_with_further_terms() {
    let host = std::process::Command::new("rustc")
        .arg("-vV")
        .output()
        .expect("rustc -vV");
    let host = String::from_utf8_lossy(&host.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("rustc -vV names the host");
    let meta = cargo_metadata(&["--filter-platform", &host]);
    let in_build: BTreeSet<&str> = meta["resolve"]["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n["id"].as_str())
        .collect();
    let notice = std::fs::read_to_string(Path::new(ROOT).join("NOTICE")).expect("NOTICE");
    let named: BTreeSet<&str> = notice
        .split(|c: char| c.is_whitespace() || ",;:.()\"".contains(c))
        .collect();
    assert!(
        notice.contains("This software is based in part on the work of the Independent JPEG Group"),
        "NOTICE lacks the IJG acknowledgement"
    );
    let mut missing = Vec::new();
    let mut checked = 0;
    for p in meta["packages"].as_array().unwrap() {
        if !in_build.contains(p["id"].as_str().unwrap()) || p["source"].is_null() {
            continue; // not built for this host, or one of ours
        }
        checked += 1;
        let name = p["name"].as_str().unwrap();
        let licence = p["license"].as_str().unwrap_or("(none declared)");
        if !permissive_alone(licence) && !named.contains(name) {
            missing.push(format!("{name} {}: {licence}", p["version"]));
        }
    }
    assert!(checked > 100, "only {checked} packages read");
    assert!(
        missing.is_empty(),
        "dependencies whose licences ask for more than MIT/Apache-2.0, not named in NOTICE:\n{}",
        missing.join("\n")
    );
}
