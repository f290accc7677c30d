//! Replays the graph fuzz corpus and crash regressions (`fuzz/corpus/graph/` and
//! `fuzz/regressions/graph/` at the repository root) through the fuzz target's own entry
//! point: every input must parse or fail with an error, never panic, and what parses must save
//! to text that loads again. `HATCHERY_FUZZ_SHOW=1` prints each file's outcome. See
//! `docs/fuzzing.md`.

#[path = "../../../fuzz/src/graph_target.rs"]
mod graph_target;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use graph_target::{Schemas, graph};

fn files(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .map(|e| e.expect("cannot list a corpus folder").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

#[test]
fn fuzz_corpus_and_regressions_parse_or_fail_cleanly() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let fuzz = fuzz.canonicalize().unwrap_or(fuzz);
    let show = std::env::var_os("HATCHERY_FUZZ_SHOW").is_some();
    let schemas = Schemas::default();
    let corpus = files(&fuzz.join("corpus/graph"));
    assert!(
        !corpus.is_empty(),
        "no graph fuzz corpus in {}",
        fuzz.display()
    );
    let regressions = files(&fuzz.join("regressions/graph"));
    let mut failures = Vec::new();
    for path in corpus.iter().chain(&regressions) {
        let data = std::fs::read(path).expect("cannot read a corpus file");
        match catch_unwind(AssertUnwindSafe(|| graph(&schemas, &data))) {
            Ok(outcome) if show => println!("{}: {outcome:?}", path.display()),
            Ok(_) => {}
            Err(_) => failures.push(path.display().to_string()),
        }
    }
    assert!(
        failures.is_empty(),
        "these inputs panic (reproduce with `cargo fuzz run graph <file>`):\n{}",
        failures.join("\n")
    );
}
