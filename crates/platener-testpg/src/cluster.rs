//! A throwaway PostgreSQL cluster: initdb in a temp dir, a server on a free loopback port.

use std::io::Read;
use std::net::{Ipv4Addr, TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crate::Error;
use crate::binaries::Binaries;
use crate::user::{RunAs, temp_base};
use crate::watchdog::Watchdog;

/// The superuser initdb creates; connections from loopback are trusted (no password).
pub const SUPERUSER: &str = "platener";
/// The database [`Cluster::start`] creates; [`Cluster::url`] points at it.
pub const DEFAULT_DATABASE: &str = "platener";
/// How long the server may take to accept connections.
const READY_SECONDS: u64 = 60;
/// Ports tried when another process takes the chosen one before the server binds it.
const PORT_ATTEMPTS: usize = 5;
/// libpq settings of the caller's environment that could send createdb elsewhere.
const LIBPQ_VARS: [&str; 11] = [
    "PGHOST",
    "PGHOSTADDR",
    "PGPORT",
    "PGUSER",
    "PGDATABASE",
    "PGSERVICE",
    "PGSERVICEFILE",
    "PGPASSFILE",
    "PGPASSWORD",
    "PGOPTIONS",
    "PGDATA",
];

/// A running throwaway cluster. Dropping it stops the server (`pg_ctl stop -m immediate`) and
/// removes its directory; so does the owning process's exit, even when it is killed (see
/// the watchdog module).
#[derive(Debug)]
pub struct Cluster {
    bins: Binaries,
    dir: PathBuf,
    port: u16,
    databases: AtomicU64,
    _watchdog: Watchdog,
}

/// One database of a cluster, made by [`Cluster::fresh_database`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Database {
    /// Its name.
    pub name: String,
    /// `postgres://platener@127.0.0.1:PORT/NAME`.
    pub url: String,
}

impl Cluster {
    /// Finds PostgreSQL, initialises a cluster in a new temp dir, starts it on a free port of
    /// 127.0.0.1, waits until it accepts connections and creates [`DEFAULT_DATABASE`].
    pub fn start() -> Result<Cluster, Error> {
        let bins = Binaries::find()?;
        let run_as = RunAs::detect()?;
        let tmp = tempfile::Builder::new()
            .prefix("platener-pg-")
            .tempdir_in(temp_base(run_as))
            .map_err(Error::io("making the cluster's temp dir"))?;
        if let Some(user) = run_as {
            user.chown(tmp.path())?;
        }
        let mut watchdog = Watchdog::spawn(&bins, run_as, tmp.path(), READY_SECONDS)?;
        // From here on the watchdog removes the directory, whatever happens.
        let dir = tmp.keep();
        watchdog.init()?;
        configure(&dir)?;
        let port = start_server(&mut watchdog, &dir)?;
        let cluster = Cluster {
            bins,
            dir,
            port,
            databases: AtomicU64::new(0),
            _watchdog: watchdog,
        };
        cluster.create_database(DEFAULT_DATABASE)?;
        Ok(cluster)
    }

    /// `postgres://platener@127.0.0.1:PORT/platener`.
    pub fn url(&self) -> String {
        self.database_url(DEFAULT_DATABASE)
    }

    /// The URL of one database of this cluster.
    pub fn database_url(&self, name: &str) -> String {
        format!("postgres://{SUPERUSER}@127.0.0.1:{}/{name}", self.port)
    }

    /// The loopback port the server listens on.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The cluster's directory (data directory, socket, log); gone after drop.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The server's process id, from its `postmaster.pid`.
    pub fn server_pid(&self) -> Result<u32, Error> {
        let path = self.dir.join("data/postmaster.pid");
        let text = std::fs::read_to_string(&path).map_err(Error::io(format!("reading {}", path.display())))?;
        text.lines()
            .next()
            .and_then(|l| l.trim().parse().ok())
            .ok_or_else(|| Error::Io {
                what: format!("reading {}", path.display()),
                source: std::io::Error::new(std::io::ErrorKind::InvalidData, "no process id on its first line"),
            })
    }

    /// A new, empty database for one test (`test_1`, `test_2`, …), so tests sharing the
    /// cluster never see each other's tables.
    pub fn fresh_database(&self) -> Result<Database, Error> {
        let n = self.databases.fetch_add(1, Ordering::Relaxed) + 1;
        let name = format!("test_{n}");
        self.create_database(&name)?;
        Ok(Database {
            url: self.database_url(&name),
            name,
        })
    }

    /// Creates a database with `createdb` over TCP (which also proves the URL works).
    pub fn create_database(&self, name: &str) -> Result<(), Error> {
        let plain = !name.is_empty()
            && name
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_');
        if !plain {
            return Err(Error::BadDatabaseName(name.into()));
        }
        let mut command = Command::new(self.bins.program("createdb"));
        command
            .args(["--no-password", "-h", "127.0.0.1", "-U", SUPERUSER, "-p"])
            .arg(self.port.to_string())
            .arg(name)
            .env("PGCONNECT_TIMEOUT", "10");
        for var in LIBPQ_VARS {
            command.env_remove(var);
        }
        run(&mut command).map(drop)
    }
}

/// The settings of a fast, loopback-only, throwaway server, after initdb's.
fn configure(dir: &Path) -> Result<(), Error> {
    let socket_dir = dir.to_string_lossy().replace('\'', "''");
    let settings = format!(
        "\n# platener-testpg: a throwaway cluster for tests\n\
         listen_addresses = '127.0.0.1'\n\
         unix_socket_directories = '{socket_dir}'\n\
         fsync = off\nsynchronous_commit = off\nfull_page_writes = off\n\
         shared_buffers = 16MB\nmax_connections = 200\n"
    );
    let conf = dir.join("data/postgresql.conf");
    let mut file = std::fs::OpenOptions::new()
        .append(true)
        .open(&conf)
        .map_err(Error::io(format!("opening {}", conf.display())))?;
    std::io::Write::write_all(&mut file, settings.as_bytes()).map_err(Error::io(format!("writing {}", conf.display())))
}

/// Starts the server on a free port, trying another port when someone else took it between
/// our probe and the server's bind (several test binaries start clusters at once).
fn start_server(watchdog: &mut Watchdog, dir: &Path) -> Result<u16, Error> {
    let log = dir.join("postgres.log");
    for _ in 0..PORT_ATTEMPTS {
        let port = free_port()?;
        let log_start = std::fs::metadata(&log).map_or(0, |m| m.len());
        let started = watchdog.start(port)?;
        let attempt_log = log_tail(&log, log_start);
        match started {
            Ok(()) => return wait_for_tcp(port, &attempt_log).map(|()| port),
            Err(_) if attempt_log.contains("Address already in use") => continue,
            Err(failed) if failed.output.contains("did not start in time") => {
                return Err(Error::NotReady {
                    port,
                    seconds: READY_SECONDS,
                    log: attempt_log,
                });
            }
            Err(mut failed) => {
                failed.output = format!("{}\nserver log:\n{attempt_log}", failed.output);
                return Err(watchdog.command_error("pg_ctl", failed));
            }
        }
    }
    Err(Error::NoFreePort {
        attempts: PORT_ATTEMPTS,
    })
}

/// A port of 127.0.0.1 that nobody listens on right now (the kernel's pick).
fn free_port() -> Result<u16, Error> {
    let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, 0)).map_err(Error::io("probing for a free port"))?;
    listener
        .local_addr()
        .map(|a| a.port())
        .map_err(Error::io("probing for a free port"))
}

/// Confirms the server takes TCP connections on 127.0.0.1 (pg_ctl's wait only watches its
/// pid file), within the same deadline.
fn wait_for_tcp(port: u16, log: &str) -> Result<(), Error> {
    let deadline = Instant::now() + Duration::from_secs(READY_SECONDS);
    let addr = (Ipv4Addr::LOCALHOST, port).into();
    while TcpStream::connect_timeout(&addr, Duration::from_secs(1)).is_err() {
        if Instant::now() > deadline {
            return Err(Error::NotReady {
                port,
                seconds: READY_SECONDS,
                log: log.to_string(),
            });
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    Ok(())
}

/// Runs a program to completion (no input), turning a failure into [`Error::Command`] with its
/// output.
fn run(command: &mut Command) -> Result<String, Error> {
    let program = PathBuf::from(command.get_program());
    let output = command
        .stdin(Stdio::null())
        .output()
        .map_err(Error::io(format!("running {}", program.display())))?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    if output.status.success() {
        Ok(text)
    } else {
        Err(Error::Command {
            program,
            status: output.status.to_string(),
            output: text.trim().to_string(),
        })
    }
}

/// What the server logged from byte `start` on (at most the last 4 kB).
fn log_tail(log: &Path, start: u64) -> String {
    let mut text = String::new();
    if let Ok(mut file) = std::fs::File::open(log) {
        let _ = std::io::Seek::seek(&mut file, std::io::SeekFrom::Start(start));
        let _ = file.read_to_string(&mut text);
    }
    let cut = text.len().saturating_sub(4096);
    let cut = (cut..text.len())
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(text.len());
    text[cut..].trim().to_string()
}
