//! Moving a graph file to another folder: relative paths in it are relative to its folder, so
//! saving it elsewhere ("Save as", Python's `save`) rewrites them to name the same files from
//! the new folder.

use std::path::{Path, PathBuf};

use crate::document::GraphDocument;
use crate::param::ParamKind;
use crate::schema::SchemaLookup;

/// Rewrites the relative path parameters of `doc` (those of kind Path in the node kinds'
/// schemas) from `doc.base_dir` to `new_dir`, as relative paths where one exists, and sets
/// `doc.base_dir` to `new_dir`. Absolute paths, empty ones and documents without a folder are
/// left as they are. Returns how many parameters changed.
pub fn rebase_paths(doc: &mut GraphDocument, schemas: &dyn SchemaLookup, new_dir: &Path) -> usize {
    let Some(old_dir) = doc.base_dir.clone() else {
        doc.base_dir = Some(new_dir.to_path_buf());
        return 0;
    };
    let (old_dir, new_dir) = (absolute(&old_dir), absolute(new_dir));
    let mut changed = 0;
    if old_dir != new_dir {
        for node in &mut doc.nodes {
            let Some(schema) = schemas.schema(&node.kind) else {
                continue;
            };
            for spec in schema
                .params
                .iter()
                .filter(|p| matches!(p.kind, ParamKind::Path))
            {
                let Some(ron::Value::String(text)) = node.params.get(spec.name) else {
                    continue;
                };
                if text.is_empty() || Path::new(text).is_absolute() {
                    continue;
                }
                // Files that exist are named by their real path (`..` and symbolic links
                // resolved); others as joined, which resolves the same way.
                let joined = old_dir.join(text);
                let (target, from) = match (joined.canonicalize(), new_dir.canonicalize()) {
                    (Ok(t), Ok(f)) => (t, f),
                    _ => (joined, new_dir.clone()),
                };
                let moved = pathdiff::diff_paths(&target, &from).unwrap_or(target);
                node.params.insert(
                    spec.name.to_owned(),
                    ron::Value::String(moved.to_string_lossy().into_owned()),
                );
                changed += 1;
            }
        }
    }
    doc.base_dir = Some(new_dir);
    changed
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::NodeDoc;
    use crate::schema::{NodeSchema, SchemaLookup};
    use crate::{ParamSpec, ParamValue};

    struct One(NodeSchema);
    impl SchemaLookup for One {
        fn schema(&self, kind: &str) -> Option<&NodeSchema> {
            (kind == self.0.kind).then_some(&self.0)
        }
        fn kinds(&self) -> Vec<&'static str> {
            vec![self.0.kind]
        }
    }

    #[test]
    fn relative_paths_name_the_same_files_from_the_new_folder() {
        let schemas = One(NodeSchema {
            kind: "Reader",
            category: "Data",
            doc: "",
            inputs: vec![],
            outputs: vec![],
            params: vec![
                ParamSpec::path("path", "", ""),
                ParamSpec::text("note", "", ""),
            ],
            frame_dependent: false,
            sink: false,
        });
        let node = |path: &str| NodeDoc {
            id: "r".into(),
            kind: "Reader".into(),
            params: [
                ("path".to_string(), ParamValue::Path(path.into()).to_ron()),
                ("note".to_string(), ron::Value::String("a/b".into())),
            ]
            .into(),
            editor: None,
            group: None,
        };
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path().canonicalize().unwrap();
        for dir in ["graphs", "data", "figures/x"] {
            std::fs::create_dir_all(root.join(dir)).unwrap();
        }
        std::fs::write(root.join("data/brain.nii.gz"), b"").unwrap();
        let mut doc = GraphDocument {
            base_dir: Some(root.join("graphs")),
            nodes: vec![node("../data/brain.nii.gz")],
            ..Default::default()
        };
        let new_dir = root.join("figures/x");
        assert_eq!(rebase_paths(&mut doc, &schemas, &new_dir), 1);
        let path = |d: &GraphDocument| d.nodes[0].params["path"].clone();
        assert_eq!(
            path(&doc),
            ron::Value::String("../../data/brain.nii.gz".into())
        );
        assert_eq!(
            doc.nodes[0].params["note"],
            ron::Value::String("a/b".into()),
            "text stays"
        );
        assert_eq!(doc.base_dir.as_deref(), Some(new_dir.as_path()));
        // A file that does not exist (yet) is named through the old folder: the same file.
        let mut missing = GraphDocument {
            base_dir: Some("/work/graphs".into()),
            nodes: vec![node("../out/x.png")],
            ..Default::default()
        };
        rebase_paths(&mut missing, &schemas, Path::new("/work/figures"));
        assert_eq!(
            path(&missing),
            ron::Value::String("../graphs/../out/x.png".into())
        );
        // The same folder, absolute paths and documents without a folder stay as they are.
        assert_eq!(rebase_paths(&mut doc, &schemas, &new_dir), 0);
        let mut abs = GraphDocument {
            base_dir: Some("/a".into()),
            nodes: vec![node("/data/x.nii")],
            ..Default::default()
        };
        assert_eq!(rebase_paths(&mut abs, &schemas, Path::new("/b")), 0);
        let mut untitled = GraphDocument {
            nodes: vec![node("x.nii")],
            ..Default::default()
        };
        assert_eq!(rebase_paths(&mut untitled, &schemas, Path::new("/b")), 0);
    }
}
