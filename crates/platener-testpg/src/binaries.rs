//! Finding the PostgreSQL server programs.
//!
//! Debian puts them in `/usr/lib/postgresql/VERSION/bin`, off the PATH (only client wrappers are
//! in /usr/bin), so the PATH alone is not enough; a PATH entry that is a symlink into such a
//! directory is followed so that its sibling programs are found too.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use crate::Error;

/// Overrides the search: the directory holding initdb, pg_ctl, postgres and createdb.
pub const BIN_DIR_VAR: &str = "PLATENER_PG_BIN";

/// Where Debian installs one directory per major version.
const DEBIAN_ROOT: &str = "/usr/lib/postgresql";

/// The programs a cluster needs, all from one installation so their versions match.
const PROGRAMS: [&str; 4] = ["initdb", "pg_ctl", "postgres", "createdb"];

/// One PostgreSQL installation's bin directory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Binaries {
    dir: PathBuf,
}

impl Binaries {
    /// Finds the programs: `PLATENER_PG_BIN`, else the PATH, else the newest version under
    /// `/usr/lib/postgresql`.
    pub fn find() -> Result<Self, Error> {
        Self::find_in(
            std::env::var_os(BIN_DIR_VAR),
            std::env::var_os("PATH"),
            Path::new(DEBIAN_ROOT),
        )
    }

    /// [`Binaries::find`] with its inputs given, so tests can point it at fake installations.
    pub fn find_in(bin_dir: Option<OsString>, path: Option<OsString>, root: &Path) -> Result<Self, Error> {
        if let Some(dir) = bin_dir {
            let dir = PathBuf::from(dir);
            return if complete(&dir) {
                Ok(Self { dir })
            } else {
                Err(Error::NotInstalled {
                    searched: format!("{BIN_DIR_VAR}={}", dir.display()),
                })
            };
        }
        let on_path = path
            .iter()
            .flat_map(std::env::split_paths)
            .find_map(|dir| from_path_entry(&dir));
        if let Some(dir) = on_path.or_else(|| newest_under(root)) {
            return Ok(Self { dir });
        }
        Err(Error::NotInstalled {
            searched: format!("the PATH and {}/*/bin", root.display()),
        })
    }

    /// The bin directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The path of one program of this installation.
    pub fn program(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
}

/// Whether `dir` holds every program a cluster needs.
fn complete(dir: &Path) -> bool {
    PROGRAMS.iter().all(|p| dir.join(p).is_file())
}

/// The installation a PATH entry leads to: the entry itself, or the directory its `initdb`
/// symlink points into.
fn from_path_entry(dir: &Path) -> Option<PathBuf> {
    let initdb = dir.join("initdb");
    if !initdb.is_file() {
        return None;
    }
    if complete(dir) {
        return Some(dir.to_path_buf());
    }
    let real = initdb.canonicalize().ok()?;
    let real_dir = real.parent()?;
    complete(real_dir).then(|| real_dir.to_path_buf())
}

/// The newest complete `ROOT/VERSION/bin`, comparing versions as numbers (16 is newer than 9.6).
fn newest_under(root: &Path) -> Option<PathBuf> {
    let mut versions: Vec<(Vec<u32>, PathBuf)> = std::fs::read_dir(root)
        .ok()?
        .flatten()
        .filter_map(|entry| {
            let name = entry.file_name().into_string().ok()?;
            let version = name.split('.').map(str::parse).collect::<Result<Vec<u32>, _>>().ok()?;
            Some((version, entry.path().join("bin")))
        })
        .filter(|(_, bin)| complete(bin))
        .collect();
    versions.sort();
    versions.pop().map(|(_, bin)| bin)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Makes a fake installation: empty files with the programs' names.
    fn fake_install(dir: &Path, programs: &[&str]) {
        std::fs::create_dir_all(dir).expect("mkdir");
        for p in programs {
            std::fs::write(dir.join(p), "").expect("write");
        }
    }

    #[test]
    fn the_newest_version_wins_by_number_not_by_text() {
        let root = tempfile::tempdir().expect("tempdir");
        for v in ["9.6", "15", "16", "notaversion"] {
            fake_install(&root.path().join(v).join("bin"), &PROGRAMS);
        }
        // A newer but incomplete installation is not chosen.
        fake_install(&root.path().join("17/bin"), &["initdb", "pg_ctl"]);
        let found = Binaries::find_in(None, Some(OsString::new()), root.path()).expect("found");
        assert_eq!(found.dir(), root.path().join("16/bin"));
    }

    #[test]
    fn a_path_symlink_leads_to_its_installation() {
        let root = tempfile::tempdir().expect("tempdir");
        let install = root.path().join("pg/15/bin");
        fake_install(&install, &PROGRAMS);
        let path_dir = root.path().join("local-bin");
        std::fs::create_dir_all(&path_dir).expect("mkdir");
        std::os::unix::fs::symlink(install.join("initdb"), path_dir.join("initdb")).expect("symlink");
        let empty_root = root.path().join("none");
        let found = Binaries::find_in(None, Some(path_dir.into_os_string()), &empty_root).expect("found");
        assert_eq!(found.dir(), install.canonicalize().expect("canonical"));
        assert_eq!(found.program("pg_ctl"), found.dir().join("pg_ctl"));
    }

    #[test]
    fn nothing_installed_is_a_clear_error() {
        let root = tempfile::tempdir().expect("tempdir");
        let err = Binaries::find_in(None, Some(OsString::new()), root.path()).expect_err("nothing there");
        assert!(matches!(err, Error::NotInstalled { .. }));
        let message = err.to_string();
        assert!(message.contains("PostgreSQL is not installed"), "{message}");
        assert!(message.contains("postgresql"), "{message}");
        let err = Binaries::find_in(Some(root.path().into()), None, root.path()).expect_err("bad override");
        assert!(err.to_string().contains(BIN_DIR_VAR), "{err}");
    }
}
