//! The throwaway cluster itself: it starts, takes connections on its URL, carries the queue
//! pattern the server relies on (`FOR UPDATE SKIP LOCKED`), gives tests separate databases, and
//! leaves nothing behind when dropped.

use std::collections::BTreeSet;

use platener_testpg::Cluster;
use sqlx::{Connection, PgConnection, Row};

/// Rows in the queue test, as the two-workers test.
const JOBS: i32 = 40;

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .expect("runtime")
}

async fn connect(url: &str) -> PgConnection {
    PgConnection::connect(url)
        .await
        .unwrap_or_else(|e| panic!("connecting to {url}: {e}"))
}

/// Claims the lowest unclaimed row that no one else has locked, for `worker`, inside the
/// caller's transaction; `None` when none is left.
async fn claim(tx: &mut PgConnection, worker: i32) -> Option<i32> {
    let row = sqlx::query("SELECT id FROM jobs WHERE claimed_by IS NULL ORDER BY id FOR UPDATE SKIP LOCKED LIMIT 1")
        .fetch_optional(&mut *tx)
        .await
        .expect("select for update");
    let id: i32 = row?.get("id");
    sqlx::query("UPDATE jobs SET claimed_by = $1, claims = claims + 1 WHERE id = $2")
        .bind(worker)
        .bind(id)
        .execute(&mut *tx)
        .await
        .expect("update");
    Some(id)
}

/// One worker: claims rows, one transaction each, until none is left.
async fn drain(url: String, worker: i32) -> Vec<i32> {
    let mut conn = connect(&url).await;
    let mut claimed = Vec::new();
    loop {
        let mut tx = conn.begin().await.expect("begin");
        let id = claim(&mut tx, worker).await;
        tx.commit().await.expect("commit");
        match id {
            Some(id) => claimed.push(id),
            None => return claimed,
        }
    }
}

#[test]
fn two_workers_claim_every_row_exactly_once() {
    let Some(cluster) = Cluster::for_tests() else { return };
    let db = cluster.fresh_database().expect("database");
    runtime().block_on(async {
        let mut setup = connect(&db.url).await;
        sqlx::query("CREATE TABLE jobs (id int PRIMARY KEY, claimed_by int, claims int NOT NULL DEFAULT 0)")
            .execute(&mut setup)
            .await
            .expect("create table");
        sqlx::query("INSERT INTO jobs (id) SELECT generate_series(1, $1)")
            .bind(JOBS)
            .execute(&mut setup)
            .await
            .expect("insert");

        // While one worker holds row 1 in an open transaction, the other neither waits nor
        // takes it: it gets row 2. This is the property the job queue needs.
        let (mut a, mut b) = (connect(&db.url).await, connect(&db.url).await);
        // Without SKIP LOCKED, b would wait for a forever: make that an error instead.
        sqlx::query("SET lock_timeout = '30s'")
            .execute(&mut b)
            .await
            .expect("lock timeout");
        let mut tx_a = a.begin().await.expect("begin a");
        let mut tx_b = b.begin().await.expect("begin b");
        assert_eq!(claim(&mut tx_a, 1).await, Some(1));
        assert_eq!(claim(&mut tx_b, 2).await, Some(2));
        tx_a.commit().await.expect("commit a");
        tx_b.commit().await.expect("commit b");

        // Then both drain the rest at the same time.
        let (left, right) = tokio::join!(
            tokio::spawn(drain(db.url.clone(), 1)),
            tokio::spawn(drain(db.url.clone(), 2))
        );
        let (left, right) = (left.expect("worker 1"), right.expect("worker 2"));
        let mut all: Vec<i32> = [vec![1, 2], left.clone(), right.clone()].concat();
        all.sort_unstable();
        assert_eq!(
            all,
            (1..=JOBS).collect::<Vec<_>>(),
            "every row claimed once: {left:?} / {right:?}"
        );

        let rows = sqlx::query("SELECT id, claimed_by, claims FROM jobs ORDER BY id")
            .fetch_all(&mut setup)
            .await
            .expect("read back");
        assert_eq!(rows.len(), JOBS as usize);
        for row in rows {
            let (id, by, claims): (i32, Option<i32>, i32) = (row.get(0), row.get(1), row.get(2));
            assert_eq!(claims, 1, "row {id} claimed {claims} times");
            let expected = if id == 1 || left.contains(&id) { 1 } else { 2 };
            assert_eq!(by, Some(expected), "row {id}");
        }
    });
}

#[test]
fn fresh_databases_are_separate() {
    let Some(cluster) = Cluster::for_tests() else { return };
    let (one, two) = (
        cluster.fresh_database().expect("one"),
        cluster.fresh_database().expect("two"),
    );
    assert_ne!(one.name, two.name);
    assert_eq!(
        one.url,
        format!("postgres://platener@127.0.0.1:{}/{}", cluster.port(), one.name)
    );
    runtime().block_on(async {
        let mut a = connect(&one.url).await;
        sqlx::query("CREATE TABLE only_here (x int)")
            .execute(&mut a)
            .await
            .expect("create");
        let mut b = connect(&two.url).await;
        let count: i64 = sqlx::query_scalar("SELECT count(*) FROM pg_tables WHERE tablename = 'only_here'")
            .fetch_one(&mut b)
            .await
            .expect("count");
        assert_eq!(count, 0, "a table of {} is visible in {}", one.name, two.name);
        let db: String = sqlx::query_scalar("SELECT current_database()")
            .fetch_one(&mut b)
            .await
            .expect("db");
        assert_eq!(db, two.name);
    });
    assert!(
        std::ptr::eq(cluster, Cluster::for_tests().expect("shared")),
        "one cluster per test binary"
    );
}

#[test]
fn bad_database_names_are_refused() {
    let Some(cluster) = Cluster::for_tests() else { return };
    for name in ["", "Robert'); DROP", "a b", "UPPER"] {
        let err = cluster.create_database(name).expect_err(name);
        assert!(err.to_string().contains("not a lower-case identifier"), "{err}");
    }
}

/// Whether a process runs (a zombie waiting for its parent to reap it counts as gone).
fn alive(pid: u32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
        stat.rsplit(')')
            .next()
            .is_some_and(|rest| !rest.trim_start().starts_with('Z'))
    })
}

#[test]
fn two_clusters_at_once_then_drop_leaves_nothing() {
    let Some(first) = Cluster::own_for_tests() else { return };
    let second = Cluster::start().expect("a second cluster");
    assert_ne!(first.port(), second.port());
    assert_ne!(first.dir(), second.dir());
    let ports: BTreeSet<u16> = [first.port(), second.port()].into();
    runtime().block_on(async {
        for cluster in [&first, &second] {
            let mut conn = connect(&cluster.url()).await;
            let port: String = sqlx::query_scalar("SHOW port")
                .fetch_one(&mut conn)
                .await
                .expect("port");
            assert!(ports.contains(&port.parse().expect("a number")));
            assert_eq!(port, cluster.port().to_string());
            let fsync: String = sqlx::query_scalar("SHOW fsync")
                .fetch_one(&mut conn)
                .await
                .expect("fsync");
            assert_eq!(fsync, "off");
            conn.close().await.expect("close");
        }
    });

    let (dir, pid, port) = (
        first.dir().to_path_buf(),
        first.server_pid().expect("pid"),
        first.port(),
    );
    assert!(dir.join("data/PG_VERSION").is_file());
    assert!(alive(pid), "server {pid} runs before drop");
    drop(first);
    assert!(!dir.exists(), "{} removed", dir.display());
    assert!(!alive(pid), "server {pid} is gone after drop");
    assert!(
        std::net::TcpStream::connect(("127.0.0.1", port)).is_err(),
        "nothing listens on {port}"
    );
    // The other cluster is untouched.
    assert!(alive(second.server_pid().expect("pid")));
}
