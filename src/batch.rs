//! `hatchery batch JOB`: renders a job's items (this process's shard of them), or `--merge`
//! checks the shards' manifests. See docs/batch.md and the hatchery-batch crate.

use anyhow::{Result, bail};
use hatchery_batch::{Outcome, Shard};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// The command's arguments (docs/batch.md).
#[derive(clap::Args)]
pub struct Args {
    /// The job file (RON).
    pub job: PathBuf,
    /// Where outputs and manifests go (default: the job file's folder).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Render items K, K+N, K+2N, … (default: the shard a Slurm array or Kubernetes
    /// Indexed Job gives through the environment, else all).
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// The number of shards where the environment gives only an index
    /// (`JOB_COMPLETION_INDEX`); also HATCHERY_SHARD_COUNT.
    #[arg(long, value_name = "N")]
    pub shard_count: Option<usize>,
    /// Check that every item is present once in the manifests and write manifest.json.
    #[arg(long)]
    pub merge: bool,
    /// Print the work list (index, output, data set, parameters) and exit.
    #[arg(long)]
    pub list: bool,
}

/// The output folder: `--out`, else the job file's folder.
fn out_dir(job: &Path, out: Option<&Path>) -> PathBuf {
    match out {
        Some(o) => o.to_path_buf(),
        None => std::path::absolute(job)
            .ok()
            .and_then(|p| p.parent().map(Path::to_path_buf))
            .unwrap_or_default(),
    }
}

/// Runs the command; returns the process's exit code (1 when an item failed or a merge found
/// problems).
pub fn command(args: Args) -> Result<i32> {
    let job = hatchery_batch::load(&args.job).map_err(anyhow::Error::msg)?;
    let out = out_dir(&args.job, args.out.as_deref());
    if args.list {
        for item in &job.items {
            let params: Vec<String> = item
                .params
                .iter()
                .map(|(n, p, v)| format!("{n}.{p}={v}"))
                .collect();
            let input = item.input.as_ref().map(|(n, _)| n.as_str()).unwrap_or("-");
            println!(
                "{}\t{}\t{input}\t{}",
                item.index,
                item.output,
                params.join(" ")
            );
        }
        return Ok(0);
    }
    if args.merge {
        let merged = hatchery_batch::manifest::merge(&job, &out).map_err(anyhow::Error::msg)?;
        for p in &merged.problems {
            eprintln!("batch: {p}");
        }
        if let Some(path) = &merged.written {
            println!(
                "batch: all {} items present once; merged manifest {}",
                merged.complete,
                path.display()
            );
            for a in &merged.animations {
                println!("batch: wrote {}", a.display());
            }
            return Ok(0);
        }
        println!(
            "batch: {} of {} items present; {} problem(s)",
            merged.complete,
            job.items.len(),
            merged.problems.len()
        );
        return Ok(1);
    }
    let shard = match &args.shard {
        Some(text) => Shard::parse(text).map_err(anyhow::Error::msg)?,
        None => Shard::from_env(|k| std::env::var(k).ok(), args.shard_count)
            .map_err(anyhow::Error::msg)?
            .unwrap_or(Shard::ALL),
    };
    let indices = shard.indices(&job);
    if indices.is_empty() {
        println!(
            "batch: shard {} has no items (the job has {})",
            shard.tag(),
            job.items.len()
        );
        return Ok(0);
    }
    eprintln!(
        "batch: {} — {} of {} items (shard {}) into {}",
        args.job.display(),
        indices.len(),
        job.items.len(),
        shard.tag(),
        out.display()
    );
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(indices.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} [{eta}]")
                .expect("a valid template"),
        );
        bar
    });
    let total = indices.len();
    let mut count = 0;
    let summary = hatchery_batch::run(
        &job,
        &out,
        &indices,
        &shard.tag(),
        &mut |item, outcome, s| {
            count += 1;
            let what = match outcome {
                Outcome::Rendered => format!("{} ({s:.2} s)", item.output),
                Outcome::Skipped => format!("{} (done before)", item.output),
                Outcome::Failed(e) => format!("{} FAILED: {e}", item.output),
            };
            match &bar {
                Some(bar) => {
                    if let Outcome::Failed(_) = outcome {
                        bar.println(format!("batch: {what}"));
                    }
                    bar.set_message(item.output.clone());
                    bar.inc(1);
                }
                None => eprintln!("batch: {count}/{total} {what}"),
            }
        },
    )
    .map_err(anyhow::Error::msg)?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    println!(
        "batch: {} rendered, {} done before, {} failed; manifest {}",
        summary.rendered,
        summary.skipped,
        summary.failed,
        summary.manifest.display()
    );
    if summary.failed > 0 {
        bail!("{} item(s) failed (see the manifest)", summary.failed);
    }
    // The whole job ran here: merge it (the merged manifest, the animations).
    if shard == Shard::ALL {
        let merged = hatchery_batch::manifest::merge(&job, &out).map_err(anyhow::Error::msg)?;
        if let Some(problem) = merged.problems.first() {
            bail!("{problem}");
        }
        for a in &merged.animations {
            println!("batch: wrote {}", a.display());
        }
    }
    Ok(0)
}
