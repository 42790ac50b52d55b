//! A test process killed with SIGKILL (no destructor runs) leaves no server and no directory:
//! the cluster's watchdog cleans up when its pipe from the owner closes.

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use platener_testpg::Cluster;

/// Set in the child process that holds a cluster until it is killed.
const CHILD: &str = "PLATENER_TESTPG_HOLD_CLUSTER";

/// The child's part: start a cluster, say where it is, then wait to be killed (at most 2 min).
#[test]
#[ignore = "run by killed_owner_leaves_nothing_behind in a child process"]
fn hold_a_cluster_until_killed() {
    assert!(
        std::env::var_os(CHILD).is_some(),
        "only run as a child of killed_owner_leaves_nothing_behind"
    );
    let cluster = Cluster::start().expect("cluster");
    println!(
        "HOLDING {} {} {}",
        cluster.server_pid().expect("pid"),
        cluster.port(),
        cluster.dir().display()
    );
    std::thread::sleep(Duration::from_secs(120));
}

/// Whether a process runs (a zombie counts as gone).
fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
        stat.rsplit(')')
            .next()
            .is_some_and(|rest| !rest.trim_start().starts_with('Z'))
    })
}

#[test]
fn killed_owner_leaves_nothing_behind() {
    if !Cluster::installed_for_tests() {
        return;
    }
    let mut child = Command::new(std::env::current_exe().expect("test binary"))
        .args(["--exact", "hold_a_cluster_until_killed", "--ignored", "--nocapture"])
        .env(CHILD, "1")
        .stdout(Stdio::piped())
        .spawn()
        .expect("child");
    let stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let line = stdout.lines().map_while(Result::ok).find(|l| l.starts_with("HOLDING "));
    let line = line.expect("the child reports its cluster");
    let mut fields = line.split_whitespace().skip(1);
    let pid: u32 = fields.next().and_then(|f| f.parse().ok()).expect("pid");
    let port: u16 = fields.next().and_then(|f| f.parse().ok()).expect("port");
    let dir: PathBuf = fields.collect::<Vec<_>>().join(" ").into();
    assert!(
        alive(pid) && dir.is_dir(),
        "the child's cluster runs in {}",
        dir.display()
    );

    child.kill().expect("SIGKILL");
    child.wait().expect("reaped");
    // Cleanup is asynchronous: wait for it, with a generous deadline that only bounds a failure.
    let deadline = Instant::now() + Duration::from_secs(60);
    while (alive(pid) || dir.exists()) && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(!alive(pid), "server {pid} still runs after its owner was killed");
    assert!(
        !dir.exists(),
        "{} still exists after its owner was killed",
        dir.display()
    );
    assert!(
        std::net::TcpStream::connect(("127.0.0.1", port)).is_err(),
        "nothing listens on {port}"
    );
}
