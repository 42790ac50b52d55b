//! Running the server as an unprivileged user when the tests run as root.
//!
//! initdb, pg_ctl and postgres refuse to run as root. Tests here run as root (containers, CI),
//! so the server programs run as `nobody`: the child process gets that user's uid and gid and no
//! supplementary groups (std's `Command::uid` clears them when the parent is root), and the
//! cluster's directory is handed to that user.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::Error;

/// The account the server programs run as when the tests run as root.
const UNPRIVILEGED_USER: &str = "nobody";

/// The user and group a child process switches to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RunAs {
    uid: u32,
    gid: u32,
}

impl RunAs {
    /// `None` when not root (the programs run as the current user), else `nobody`'s ids.
    pub(crate) fn detect() -> Result<Option<RunAs>, Error> {
        if !nix::unistd::geteuid().is_root() {
            return Ok(None);
        }
        let user = nix::unistd::User::from_name(UNPRIVILEGED_USER)
            .ok()
            .flatten()
            .ok_or_else(|| Error::NoUnprivilegedUser {
                user: UNPRIVILEGED_USER.into(),
            })?;
        Ok(Some(RunAs {
            uid: user.uid.as_raw(),
            gid: user.gid.as_raw(),
        }))
    }

    /// Makes `command` run as this user.
    pub(crate) fn apply(self, command: &mut Command) {
        command.uid(self.uid).gid(self.gid);
    }

    /// Hands `path` (one directory, still empty) to this user.
    pub(crate) fn chown(self, path: &Path) -> Result<(), Error> {
        std::os::unix::fs::chown(path, Some(self.uid), Some(self.gid)).map_err(Error::io(format!(
            "handing {} to uid {}",
            path.display(),
            self.uid
        )))
    }
}

/// Where the cluster's directory goes: the temp dir, unless an unprivileged user must reach it
/// and cannot (a `TMPDIR` under /root, say), then `/tmp`.
pub(crate) fn temp_base(run_as: Option<RunAs>) -> PathBuf {
    let base = std::env::temp_dir();
    if run_as.is_none() || others_can_traverse(&base) {
        base
    } else {
        PathBuf::from("/tmp")
    }
}

/// Whether every directory from `/` down to `dir` lets other users through (execute bit).
fn others_can_traverse(dir: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt;
    dir.ancestors()
        .all(|d| std::fs::metadata(d).is_ok_and(|m| m.permissions().mode() & 0o001 != 0))
}
