//! The process that owns a cluster's server: it runs initdb and `pg_ctl start` when asked, and
//! stops the server and removes the directory when its owner goes away.
//!
//! A cluster shared by a test binary lives in a static, and Rust never drops statics; a test
//! process may also be killed mid-run. So each cluster has a small `sh` watchdog that reads
//! steps from a pipe whose only writer is the owning process. When the owner drops the cluster,
//! exits or is killed, the pipe closes and the watchdog runs `pg_ctl stop -m immediate` and
//! removes the directory. Because the watchdog itself runs initdb and `pg_ctl start`, one after
//! the other, a kill in the middle of starting cannot race the cleanup: the step in progress
//! ends first (a first version ran them from the owner, and a kill during start left a
//! directory behind). It runs as the server's user, in its own process group so that Ctrl-C on
//! the test run does not stop it before it has cleaned up, and ignores SIGPIPE so that answering
//! a dead owner does not kill it.

use std::io::{BufRead, BufReader, Write};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use crate::Error;
use crate::binaries::Binaries;
use crate::cluster::SUPERUSER;
use crate::user::RunAs;

/// `$1` is the bin directory, `$PLATENER_PG_DIR` the cluster's directory. Each step's output
/// goes to `step.out`; its exit status is the answer line.
const SCRIPT: &str = r#"
trap '' PIPE
bin=$1; dir=$PLATENER_PG_DIR; data=$dir/data
while read -r step arg; do
  case $step in
    init) "$bin/initdb" -D "$data" -U "$PLATENER_PG_USER" --auth=trust --encoding=UTF8 --locale=C \
            --no-sync --no-instructions ;;
    start) "$bin/pg_ctl" start -w -s -t "$PLATENER_PG_WAIT" -D "$data" -l "$dir/postgres.log" -o "-p $arg" ;;
    *) echo "unknown step $step"; false ;;
  esac </dev/null >"$dir/step.out" 2>&1
  echo $?
done
"$bin/pg_ctl" stop -m immediate -w -t 60 -D "$data" >/dev/null 2>&1
rm -rf -- "$dir"
"#;

/// A running watchdog; dropping it stops the server, removes the directory and waits until
/// both are done.
#[derive(Debug)]
pub(crate) struct Watchdog {
    child: Child,
    steps: Option<ChildStdin>,
    answers: BufReader<ChildStdout>,
    bins: Binaries,
    dir: PathBuf,
}

/// A step that ran and failed: its exit status and output.
pub(crate) struct StepFailed {
    pub(crate) status: String,
    pub(crate) output: String,
}

impl Watchdog {
    /// Starts the watchdog of the cluster in `dir` (its data directory will be `dir/data`);
    /// `wait_s` is how long `pg_ctl start` waits for the server to accept connections.
    pub(crate) fn spawn(bins: &Binaries, run_as: Option<RunAs>, dir: &Path, wait_s: u64) -> Result<Watchdog, Error> {
        let mut command = Command::new("sh");
        command
            .args(["-c", SCRIPT, "platener-pg-watchdog"])
            .arg(bins.dir())
            .env("PLATENER_PG_DIR", dir)
            .env("PLATENER_PG_USER", SUPERUSER)
            .env("PLATENER_PG_WAIT", wait_s.to_string())
            // Messages in English, so that "Address already in use" can be recognised.
            .env("LC_ALL", "C")
            .env("LANG", "C")
            .env_remove("PGDATA")
            // Root's working directory may be closed to the unprivileged user.
            .current_dir(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .process_group(0);
        if let Some(user) = run_as {
            user.apply(&mut command);
        }
        let mut child = command
            .spawn()
            .map_err(Error::io("starting the cluster's watchdog (sh)"))?;
        let (steps, answers) = (child.stdin.take(), child.stdout.take());
        let answers = BufReader::new(answers.ok_or_else(|| broken("no pipe from the watchdog"))?);
        Ok(Watchdog {
            child,
            steps,
            answers,
            bins: bins.clone(),
            dir: dir.to_path_buf(),
        })
    }

    /// Runs `initdb` for the data directory.
    pub(crate) fn init(&mut self) -> Result<(), Error> {
        self.step("init", "")?
            .map_err(|failed| self.command_error("initdb", failed))
    }

    /// Runs `pg_ctl start` on `port`: `Err` carries pg_ctl's status and output.
    pub(crate) fn start(&mut self, port: u16) -> Result<Result<(), StepFailed>, Error> {
        self.step("start", &port.to_string())
    }

    /// The error for a failed step of `program`.
    pub(crate) fn command_error(&self, program: &str, failed: StepFailed) -> Error {
        Error::Command {
            program: self.bins.program(program),
            status: failed.status,
            output: failed.output,
        }
    }

    /// Asks for one step and waits for its answer.
    fn step(&mut self, step: &str, arg: &str) -> Result<Result<(), StepFailed>, Error> {
        let steps = self
            .steps
            .as_mut()
            .ok_or_else(|| broken("the watchdog's pipe is closed"))?;
        writeln!(steps, "{step} {arg}")
            .and_then(|()| steps.flush())
            .map_err(Error::io(format!("asking the watchdog to {step}")))?;
        let mut answer = String::new();
        self.answers
            .read_line(&mut answer)
            .map_err(Error::io(format!("waiting for the watchdog's {step}")))?;
        let output = std::fs::read_to_string(self.dir.join("step.out"))
            .unwrap_or_default()
            .trim()
            .to_string();
        match answer.trim() {
            "0" => Ok(Ok(())),
            "" => Err(broken("the watchdog ended")),
            status => Ok(Err(StepFailed {
                status: format!("exit status {status}"),
                output,
            })),
        }
    }
}

fn broken(what: &str) -> Error {
    Error::Io {
        what: what.into(),
        source: std::io::Error::new(std::io::ErrorKind::BrokenPipe, "watchdog"),
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        drop(self.steps.take());
        // Waiting makes drop synchronous: when it returns, the server is gone and so is the
        // directory. An error here (the watchdog was killed) leaves nothing to do.
        let _ = self.child.wait();
    }
}
