//! Replays the fuzz corpora and crash regressions of the file readers (`fuzz/corpus/<target>/`
//! and `fuzz/regressions/<target>/` at the repository root) through the fuzz targets' own
//! entry points: every input must load or fail with an error naming the file, never panic.
//! `HATCHERY_FUZZ_SHOW=1` prints each file's outcome. See `docs/fuzzing.md`.

#[allow(dead_code)]
#[path = "../../../fuzz/src/data_targets.rs"]
mod data_targets;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use data_targets::{Scratch, TARGETS};

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
fn fuzz_corpus_and_regressions_load_or_fail_cleanly() {
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let fuzz = fuzz.canonicalize().unwrap_or(fuzz);
    let show = std::env::var_os("HATCHERY_FUZZ_SHOW").is_some();
    let scratch = Scratch::new();
    let mut failures = Vec::new();
    for (name, target) in TARGETS {
        let corpus = files(&fuzz.join("corpus").join(name));
        assert!(
            !corpus.is_empty(),
            "no corpus for fuzz target `{name}` in {}",
            fuzz.display()
        );
        let regressions = files(&fuzz.join("regressions").join(name));
        for path in corpus.iter().chain(&regressions) {
            let data = std::fs::read(path).expect("cannot read a corpus file");
            match catch_unwind(AssertUnwindSafe(|| target(&scratch, &data))) {
                Ok(outcome) if show => println!("{}: {outcome:?}", path.display()),
                Ok(_) => {}
                Err(_) => failures.push(path.display().to_string()),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "these inputs panic (reproduce with `cargo fuzz run <target> <file>`):\n{}",
        failures.join("\n")
    );
}
