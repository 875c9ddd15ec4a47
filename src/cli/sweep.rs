//! `rover sweep plan.toml --index I --count N`: worker I of N runs its
//! share of a sweep plan's tasks (see [`rover_scenario::sweep`]); `--gather`
//! collects the records into `results.csv`.

use std::path::PathBuf;

use clap::Args;

use rover_scenario::output::write_whole;
use rover_scenario::sweep::{Plan, SweepError, gather_csv, worker_tasks};

use crate::error::CliError;

/// Arguments of `rover sweep`.
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The sweep plan (TOML): base scenario, grid, samples, seeds.
    pub plan: PathBuf,
    /// This worker's number, from 0 (a job array's task id:
    /// `$SLURM_ARRAY_TASK_ID`, `$JOB_COMPLETION_INDEX`).
    #[arg(long, default_value_t = 0)]
    pub index: usize,
    /// How many workers share the plan; worker I runs tasks I, I + N, I + 2N, ...
    #[arg(long, default_value_t = 1)]
    pub count: usize,
    /// Instead of running, gather every task's record into `results.csv`
    /// (an error, after writing it, when a record is missing or unreadable).
    #[arg(long)]
    pub gather: bool,
    /// Check the plan's every task and print their number.
    #[arg(long)]
    pub list: bool,
}

/// Run this worker's tasks whose records do not exist yet, each record
/// written whole as soon as its run ends; or gather. The plan is checked
/// whole ([`Plan::check`]) before a task runs or the tasks are counted.
pub fn sweep(args: &SweepArgs) -> Result<(), CliError> {
    let plan = Plan::load(&args.plan)?;
    if args.gather {
        let gathered = gather_csv(&plan)?;
        if !gathered.complete() {
            return Err(SweepError::Incomplete(gathered).into());
        }
        eprintln!("wrote {}", gathered.table.display());
        return Ok(());
    }
    if !args.list && (args.count == 0 || args.index >= args.count) {
        return Err(CliError::Usage(format!(
            "--index {} --count {}: give 0 ≤ index < count",
            args.index, args.count
        )));
    }
    plan.check()?;
    if args.list {
        println!("{}", plan.tasks.len());
        return Ok(());
    }
    let dir = plan.out.join("tasks");
    rover_files::OutputDir::create(&dir).map_err(|e| CliError::io(&dir, "create", e))?;
    let (mut ran, mut skipped) = (0, 0);
    for i in worker_tasks(plan.tasks.len(), args.index, args.count) {
        let path = plan.task_path(i);
        if path.exists() {
            skipped += 1;
            continue;
        }
        let record = plan.run_task(i);
        write_whole(&path, &format!("{record}\n"))?;
        ran += 1;
    }
    eprintln!(
        "worker {} of {}: {ran} tasks run, {skipped} already done; records in {}",
        args.index,
        args.count,
        dir.display()
    );
    Ok(())
}
