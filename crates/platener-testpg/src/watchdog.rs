//! The process that stops a cluster and removes its directory when its owner goes away.
//!
//! A cluster shared by a test binary lives in a static, and Rust never drops statics: without
//! help, every test run would leave a postgres server and its directory behind, as would a test
//! process killed mid-run. So each cluster has a small `sh` watchdog that blocks reading a pipe
//! whose only writer is the owning process. When the owner drops the cluster, or exits, or is
//! killed, the pipe closes, the read ends, and the watchdog runs `pg_ctl stop -m immediate` and
//! removes the directory. It runs as the server's user and in its own process group, so Ctrl-C on
//! the test run does not kill it before it has cleaned up.

use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};

use crate::Error;
use crate::binaries::Binaries;
use crate::user::RunAs;

/// Waits for EOF on stdin, then stops the server ("$@") and removes the directory.
const SCRIPT: &str = r#"cat >/dev/null; "$@" >/dev/null 2>&1; rm -rf -- "$PLATENER_PG_DIR""#;

/// A running watchdog; dropping it cleans up and waits until that is done.
#[derive(Debug)]
pub(crate) struct Watchdog {
    child: Child,
    pipe: Option<ChildStdin>,
}

impl Watchdog {
    /// Starts the watchdog of the cluster in `dir` (its data directory is `dir/data`).
    pub(crate) fn spawn(bins: &Binaries, run_as: Option<RunAs>, dir: &Path) -> Result<Watchdog, Error> {
        let mut command = Command::new("sh");
        command
            .arg("-c")
            .arg(SCRIPT)
            .arg("platener-pg-watchdog")
            .arg(bins.program("pg_ctl"))
            .args(["stop", "-m", "immediate", "-w", "-t", "60", "-D"])
            .arg(dir.join("data"))
            .env("PLATENER_PG_DIR", dir)
            .current_dir(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .process_group(0);
        if let Some(user) = run_as {
            user.apply(&mut command);
        }
        let mut child = command
            .spawn()
            .map_err(Error::io("starting the cluster's watchdog (sh)"))?;
        let pipe = child.stdin.take();
        Ok(Watchdog { child, pipe })
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        drop(self.pipe.take());
        // Waiting makes drop synchronous: when it returns, the server is gone and so is the
        // directory. An error here (the watchdog was killed) leaves nothing to do.
        let _ = self.child.wait();
    }
}
