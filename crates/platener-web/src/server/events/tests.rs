//! The event hub: late subscribers, deletion, shutdown, many jobs in one poll, and
//! PostgreSQL's notifications. Polls are driven by hand where the poller's timing would
//! otherwise decide what a test sees; waits are bounded only to turn a hang into a failure.

use std::sync::Arc;
use std::time::Duration;

use futures_util::FutureExt as _;
use tokio::sync::watch;

use super::{Hub, Subscription};
use crate::db::{Db, EventRow, Finished, NewJob, now_ms};
use crate::ids;

/// Bounds a wait that should end at once, so a bug fails the test instead of hanging it.
const HANG: Duration = Duration::from_secs(30);
/// A poll period no test waits for: only explicit polls and notifications deliver events.
const NEVER: Duration = Duration::from_secs(3600);

async fn sqlite(dir: &tempfile::TempDir) -> Db {
    let url = format!("sqlite://{}?mode=rwc", dir.path().join("e.sqlite").display());
    Db::connect(&url, 4).await.expect("database")
}

async fn new_job(db: &Db) -> String {
    let id = ids::conversion_id();
    let job = NewJob {
        id: id.clone(),
        name: "box.stl".into(),
        model: vec![1, 2, 3],
        triangles: Some(12),
        settings: "{}".into(),
        created: now_ms(),
        delete_token_hash: ids::hash_token("t"),
        published: None,
        parent: None,
    };
    db.insert_job(&job).await.expect("insert");
    id
}

async fn steps(db: &Db, id: &str, from: usize, to: usize) {
    for i in from..=to {
        db.append_event(id, "step", &format!(r#"{{"n":{i}}}"#))
            .await
            .expect("append");
    }
}

/// The events a subscription has now, without waiting; and whether it ended.
fn ready(sub: &mut Subscription) -> (Vec<EventRow>, bool) {
    let mut out = Vec::new();
    loop {
        match sub.next().now_or_never() {
            Some(Some(e)) => out.push(e),
            Some(None) => return (out, true),
            None => return (out, false),
        }
    }
}

fn seqs(events: &[EventRow]) -> Vec<i64> {
    events.iter().map(|e| e.seq).collect()
}

#[tokio::test]
async fn a_late_subscriber_sees_the_same_events_as_an_early_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = sqlite(&dir).await;
    let (_stop, stopping) = watch::channel(false);
    let hub = Hub::new(db.clone(), NEVER);
    let id = new_job(&db).await;
    let mut early = Subscription::new(hub.subscribe(&id), stopping.clone());
    steps(&db, &id, 1, 4).await;
    hub.poll(false).await.expect("poll");
    let (mut seen_early, ended) = ready(&mut early);
    assert_eq!((seqs(&seen_early), ended), (vec![1, 2, 3, 4], false));

    // A client joins in the middle; events it missed and new ones arrive in one poll.
    steps(&db, &id, 5, 7).await;
    let mut late = Subscription::new(hub.subscribe(&id), stopping.clone());
    hub.poll(false).await.expect("poll");
    let (mut seen_late, _) = ready(&mut late);
    assert_eq!(seqs(&seen_late), (1..=7).collect::<Vec<_>>());
    db.append_event(&id, "done", r#"{"status":"done"}"#)
        .await
        .expect("done");
    // Polling twice reads the same rows twice: nothing is appended twice.
    hub.poll(true).await.expect("poll");
    hub.poll(true).await.expect("poll");
    for (sub, seen) in [(&mut early, &mut seen_early), (&mut late, &mut seen_late)] {
        let (more, ended) = ready(sub);
        assert!(ended, "the stream ends after done");
        seen.extend(more);
    }
    assert_eq!(seen_early, seen_late);
    assert_eq!(seqs(&seen_late), (1..=8).collect::<Vec<_>>());
    assert_eq!(seen_late.last().map(|e| e.kind.as_str()), Some("done"));
    assert_eq!(seen_late[4].data, r#"{"n":5}"#);

    // After the end: a client of the still-watched feed gets everything at once; once no
    // one watches, the feed is dropped and a new client reads it all from the database.
    let mut after = Subscription::new(hub.subscribe(&id), stopping.clone());
    assert_eq!(ready(&mut after), (seen_late.clone(), true));
    drop((early, late, after));
    hub.poll(true).await.expect("poll");
    assert_eq!(hub.watched(), 0);
    let mut fresh = Subscription::new(hub.subscribe(&id), stopping);
    assert_eq!(ready(&mut fresh), (Vec::new(), false), "nothing before a poll");
    hub.poll(false).await.expect("poll");
    assert_eq!(ready(&mut fresh), (seen_late, true));
}

#[tokio::test]
async fn deleting_the_job_or_stopping_the_server_ends_its_streams() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = sqlite(&dir).await;
    let (stop, stopping) = watch::channel(false);
    let hub = Hub::new(db.clone(), NEVER);
    let (deleted, kept) = (new_job(&db).await, new_job(&db).await);
    let mut gone = Subscription::new(hub.subscribe(&deleted), stopping.clone());
    let mut other = Subscription::new(hub.subscribe(&kept), stopping);
    steps(&db, &deleted, 1, 2).await;
    hub.poll(false).await.expect("poll");
    assert_eq!(seqs(&ready(&mut gone).0), vec![1, 2]);
    assert!(db.delete(&deleted).await.expect("delete"));
    // Urgent polls read events only; the full poll finds deleted jobs.
    hub.poll(false).await.expect("poll");
    assert_eq!(ready(&mut gone), (Vec::new(), false));
    hub.poll(true).await.expect("poll");
    assert_eq!(ready(&mut gone), (Vec::new(), true));
    assert_eq!(ready(&mut other), (Vec::new(), false), "the other job's stream stays");
    // A stream waiting for its next event ends when the server stops.
    let waiting = tokio::spawn(async move { other.next().await });
    tokio::task::yield_now().await;
    stop.send_replace(true);
    let next = tokio::time::timeout(HANG, waiting).await.expect("ends").expect("task");
    assert_eq!(next, None);
}

#[tokio::test]
async fn one_poll_reads_the_events_of_hundreds_of_jobs() {
    let dir = tempfile::tempdir().expect("tempdir");
    let db = sqlite(&dir).await;
    let (_stop, stopping) = watch::channel(false);
    let hub = Hub::new(db.clone(), NEVER);
    // More jobs than one query takes (200), each with 1 to 3 events.
    let mut subs = Vec::new();
    for i in 0..450 {
        let id = new_job(&db).await;
        steps(&db, &id, 1, i % 3 + 1).await;
        subs.push((i % 3 + 1, Subscription::new(hub.subscribe(&id), stopping.clone())));
    }
    assert_eq!(hub.watched(), 450);
    hub.poll(false).await.expect("one poll");
    for (n, sub) in &mut subs {
        let (events, ended) = ready(sub);
        assert_eq!(seqs(&events), (1..=*n as i64).collect::<Vec<_>>());
        assert!(!ended);
    }
}

/// On PostgreSQL, a worker's events (one by one, and the last one in `finish`'s transaction)
/// reach a stream through `NOTIFY` alone: the hub's timer never fires during the test.
#[tokio::test]
async fn postgres_notifications_wake_the_poller() {
    let Some(cluster) = platener_testpg::Cluster::for_tests() else {
        return;
    };
    let pg = cluster.fresh_database().expect("a database of this test's own");
    let db = Db::connect(&pg.url, 4).await.expect("PostgreSQL");
    let (_stop, stopping) = watch::channel(false);
    let hub: Arc<Hub> = Hub::new(db.clone(), NEVER);
    hub.start(Some(pg.url.clone()), stopping.clone());
    let mut listening = hub.listening.subscribe();
    tokio::time::timeout(HANG, listening.wait_for(|l| *l))
        .await
        .expect("the listener connects")
        .expect("hub alive");
    let id = new_job(&db).await;
    let mut sub = Subscription::new(hub.subscribe(&id), stopping);
    // The subscription's own poll, done here so that only notifications are left to act.
    hub.poll(false).await.expect("poll");
    let claimed = db.claim("w1", 30_000).await.expect("claim").expect("a job");
    assert_eq!(claimed.id, id);
    steps(&db, &id, 1, 2).await;
    let outcome = Finished {
        status: "done".into(),
        error: None,
        summary: "{}".into(),
        files: Vec::new(),
        event: r#"{"status":"done"}"#.into(),
    };
    assert!(db.finish(&id, "w1", &outcome).await.expect("finish"));
    let mut seen = Vec::new();
    while let Some(e) = tokio::time::timeout(HANG, sub.next()).await.expect("notified in time") {
        seen.push((e.seq, e.kind));
    }
    assert_eq!(seen, vec![(1, "step".into()), (2, "step".into()), (3, "done".into())]);
}
