//! The job queue: claims, leases, retries, results in one transaction, events, gallery
//! order. In-process, on SQLite in a temp dir, and again on PostgreSQL: a database of the
//! test's own in the test binary's throwaway cluster (crates/platener-testpg; skipped with a
//! message when PostgreSQL is not installed, a failure under `PLATENER_REQUIRE_POSTGRES=1`).

use platener_web::db::{Db, Finished, Hold, NewJob, ResultFile, now_ms};
use platener_web::ids;

/// The databases a test runs on: SQLite in `dir`, and a fresh PostgreSQL database when
/// PostgreSQL is installed.
async fn databases(dir: &tempfile::TempDir) -> Vec<Db> {
    let url = format!("sqlite://{}?mode=rwc", dir.path().join("q.sqlite").display());
    let mut all = vec![Db::connect(&url, 4).await.expect("database")];
    if let Some(cluster) = platener_testpg::Cluster::for_tests() {
        let pg = cluster
            .fresh_database()
            .expect("a PostgreSQL database of this test's own");
        all.push(Db::connect(&pg.url, 4).await.expect("PostgreSQL"));
    }
    all
}

fn job(created: i64) -> NewJob {
    NewJob {
        id: ids::conversion_id(),
        name: "box.stl".into(),
        model: vec![1, 2, 3],
        triangles: Some(12),
        settings: "{}".into(),
        created,
        delete_token_hash: ids::hash_token("t"),
        published: None,
        parent: None,
    }
}

fn finished(files: usize) -> Finished {
    Finished {
        status: "done".into(),
        error: None,
        summary: r#"{"best":"plate"}"#.into(),
        files: (0..files)
            .map(|i| ResultFile {
                method: "plate".into(),
                file: format!("sheets/{}.svg", i + 1),
                content_type: "image/svg+xml".into(),
                data: vec![b'<'; 10],
            })
            .collect(),
        event: r#"{"status":"done"}"#.into(),
    }
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .expect("runtime")
}

#[test]
fn claims_take_the_oldest_job_once() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let (old, new) = (job(1000), job(2000));
            db.insert_job(&new).await.expect("insert");
            db.insert_job(&old).await.expect("insert");
            assert_eq!(db.queue_len().await.expect("len"), 2);
            let a = db.claim("w1", 60_000).await.expect("claim").expect("a job");
            assert_eq!(a.id, old.id, "oldest first");
            assert_eq!((a.attempts, a.model.as_slice()), (1, &[1u8, 2, 3][..]));
            let b = db.claim("w2", 60_000).await.expect("claim").expect("a job");
            assert_eq!(b.id, new.id);
            assert!(db.claim("w3", 60_000).await.expect("claim").is_none(), "each job once");
            let row = db.job(&a.id).await.expect("read").expect("row");
            assert_eq!((row.status.as_str(), row.worker.as_deref()), ("running", Some("w1")));
            assert!(db.heartbeat(&a.id, "w1", 60_000).await.expect("beat"));
            assert!(!db.heartbeat(&a.id, "w2", 60_000).await.expect("beat"), "not w2's job");
        }
    });
}

#[test]
fn an_expired_lease_requeues_then_fails_after_two_attempts() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let j = job(now_ms());
            db.insert_job(&j).await.expect("insert");
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            assert_eq!(db.reap(2).await.expect("reap"), (vec![], vec![]), "a live lease stays");
            db.expire_worker("w1").await.expect("expire");
            assert_eq!(db.reap(2).await.expect("reap"), (vec![j.id.clone()], vec![]));
            assert_eq!(db.job(&j.id).await.expect("read").expect("row").status, "queued");
            let again = db.claim("w2", 60_000).await.expect("claim").expect("job");
            assert_eq!(again.attempts, 2);
            // A worker that lost its job cannot record it.
            db.expire_worker("w2").await.expect("expire");
            assert_eq!(db.reap(2).await.expect("reap"), (vec![], vec![j.id.clone()]));
            assert!(!db.finish(&j.id, "w2", &finished(1)).await.expect("finish"));
            let row = db.job(&j.id).await.expect("read").expect("row");
            assert_eq!(row.status, "failed");
            let error: serde_json::Value = serde_json::from_str(row.error.as_deref().expect("error")).expect("json");
            assert_eq!(error["code"], "worker_died");
            assert!(
                db.result_index(&j.id).await.expect("index").is_empty(),
                "nothing half-written"
            );
            let events = db.events_after(&j.id, 0, 100).await.expect("events");
            let kinds: Vec<&str> = events.iter().map(|e| e.kind.as_str()).collect();
            assert_eq!(kinds, ["retry", "failed"]);
            assert_eq!(events.iter().map(|e| e.seq).collect::<Vec<_>>(), [1, 2]);
        }
    });
}

/// A gone worker's jobs end with the server's reason: retried with it while attempts remain,
/// failed with its code after; an ending without retry fails at once. Only that worker's
/// running jobs are touched, and what `held_by` reports is what it holds.
#[test]
fn a_released_worker_s_job_ends_with_the_reason_given() {
    use platener_web::db::Ending;
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let (a, b) = (job(now_ms()), job(now_ms() + 1));
            db.insert_job(&a).await.expect("insert");
            db.insert_job(&b).await.expect("insert");
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            db.claim("w2", 60_000).await.expect("claim").expect("job");
            let held = db.held_by("w1").await.expect("held").expect("a job");
            assert_eq!((held.id.as_str(), held.attempts), (a.id.as_str(), 1));
            assert!(held.lease_until.is_some_and(|l| l > now_ms()));
            let oom = Ending {
                code: "out_of_memory",
                message: "ran out of memory".into(),
                retry: Some("the worker ran out of memory".into()),
            };
            assert_eq!(
                db.release_worker("w1", &oom, 2).await.expect("release"),
                (vec![a.id.clone()], vec![])
            );
            assert_eq!(db.held_by("w1").await.expect("held"), None);
            assert_eq!(db.held_by("w2").await.expect("held").map(|h| h.id), Some(b.id.clone()));
            db.claim("w3", 60_000).await.expect("claim").expect("job");
            assert_eq!(
                db.release_worker("w3", &oom, 2).await.expect("release"),
                (vec![], vec![a.id.clone()])
            );
            let row = db.job(&a.id).await.expect("read").expect("row");
            let error: serde_json::Value = serde_json::from_str(row.error.as_deref().expect("error")).expect("json");
            assert_eq!(
                (row.status.as_str(), error["code"].as_str()),
                ("failed", Some("out_of_memory"))
            );
            let kinds: Vec<String> = db
                .events_after(&a.id, 0, 100)
                .await
                .expect("events")
                .into_iter()
                .map(|e| e.kind)
                .collect();
            assert_eq!(kinds, ["retry", "failed"]);
            let overtime = Ending {
                code: "timed_out",
                message: "ran past the time limit".into(),
                retry: None,
            };
            assert_eq!(
                db.release_worker("w2", &overtime, 2).await.expect("release"),
                (vec![], vec![b.id.clone()])
            );
            let stats = db.queue_stats().await.expect("stats");
            assert_eq!((stats.queued, stats.running, stats.oldest_created), (0, 0, None));
        }
    });
}

#[test]
fn results_status_and_last_event_are_written_together() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let j = job(now_ms());
            db.insert_job(&j).await.expect("insert");
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            db.append_event(&j.id, "step", "{}").await.expect("event");
            assert!(db.finish(&j.id, "w1", &finished(3)).await.expect("finish"));
            let row = db.job(&j.id).await.expect("read").expect("row");
            assert_eq!(row.status, "done");
            assert!(row.finished.is_some() && row.summary.is_some());
            let index = db.result_index(&j.id).await.expect("index");
            assert_eq!(index.len(), 3);
            let (ct, data) = db
                .result_file(&j.id, "plate", "sheets/2.svg")
                .await
                .expect("read")
                .expect("file");
            assert_eq!((ct.as_str(), data.len()), ("image/svg+xml", 10));
            let events = db.events_after(&j.id, 1, 100).await.expect("events");
            assert_eq!(events.len(), 1);
            assert_eq!((events[0].seq, events[0].kind.as_str()), (2, "done"));
            // Finishing twice does nothing: the job is no longer running.
            assert!(!db.finish(&j.id, "w1", &finished(3)).await.expect("finish"));
            assert_eq!(db.result_index(&j.id).await.expect("index").len(), 3);
            assert!(db.delete(&j.id).await.expect("delete"));
            assert!(db.job(&j.id).await.expect("read").is_none());
            // Deleted while running: the worker's late events and results are dropped.
            let k = job(now_ms());
            db.insert_job(&k).await.expect("insert");
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            assert!(db.delete(&k.id).await.expect("delete"));
            db.append_event(&k.id, "step", "{}").await.expect("a late event");
            assert!(!db.finish(&k.id, "w1", &finished(2)).await.expect("finish"));
            assert!(db.events_after(&k.id, 0, 100).await.expect("events").is_empty());
            assert!(db.result_index(&k.id).await.expect("index").is_empty());
            assert!(db.result_index(&j.id).await.expect("index").is_empty());
            assert!(db.events_after(&j.id, 0, 100).await.expect("events").is_empty());
        }
    });
}

#[test]
fn a_graceful_stop_requeues_without_counting_and_the_gallery_is_newest_first() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let j = job(now_ms());
            db.insert_job(&j).await.expect("insert");
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            assert_eq!(db.requeue_worker("w1").await.expect("requeue"), 1);
            let row = db.job(&j.id).await.expect("read").expect("row");
            assert_eq!((row.status.as_str(), row.attempts), ("queued", 0));

            let mut ids = Vec::new();
            for i in 0..3 {
                let mut p = job(now_ms());
                p.published = Some(1000 + i);
                db.insert_job(&p).await.expect("insert");
                ids.push(p.id);
            }
            let page = db.gallery(1, 2).await.expect("gallery");
            assert_eq!(
                page.iter().map(|r| r.id.clone()).collect::<Vec<_>>(),
                [ids[2].clone(), ids[1].clone()]
            );
            let page2 = db.gallery(2, 2).await.expect("gallery");
            assert_eq!(page2.len(), 1);
            assert_eq!(page2[0].id, ids[0]);
            db.publish(&j.id).await.expect("publish");
            assert_eq!(db.gallery(1, 10).await.expect("gallery").len(), 4);
            assert!(db.set_meta_once("k", "v").await.expect("meta"));
            assert!(!db.set_meta_once("k", "w").await.expect("meta"));
            assert_eq!(db.meta("k").await.expect("meta").as_deref(), Some("v"));
        }
    });
}

/// A plate file of a running job, landed before the job ends.
fn landed_file(file: &str) -> ResultFile {
    ResultFile {
        method: "plate".into(),
        file: file.into(),
        content_type: "application/zip".into(),
        data: vec![b'P', b'K'],
    }
}

/// A new job claimed by `worker`: the hold of that attempt.
async fn claimed_job(db: &Db, worker: &str) -> Hold {
    let j = job(now_ms());
    db.insert_job(&j).await.expect("insert");
    let claimed = db.claim(worker, 60_000).await.expect("claim").expect("job");
    Hold {
        id: claimed.id,
        worker: worker.into(),
        attempt: claimed.attempts,
    }
}

/// The kinds of a job's events, in order.
async fn kinds(db: &Db, id: &str) -> Vec<String> {
    let events = db.events_after(id, 0, 100).await.expect("events");
    events.into_iter().map(|e| e.kind).collect()
}

/// The event of a landed method.
const LANDED: (&str, &str) = ("method", r#"{"method":"plate"}"#);

/// Results as they come (issue 30): a running job's files land with its summary so far and
/// their event only while the attempt that writes them holds it; the end keeps them.
#[test]
fn results_land_only_for_the_attempt_holding_the_job() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let hold = claimed_job(&db, "w1").await;
            let summary = r#"{"methods":[1]}"#;
            assert!(
                db.land(&hold, summary, &[landed_file("plan.zip")], LANDED)
                    .await
                    .expect("land")
            );
            let stale = Hold {
                attempt: 2,
                ..hold.clone()
            };
            assert!(
                !db.land(&stale, "{}", &[landed_file("other.zip")], LANDED)
                    .await
                    .expect("land")
            );
            let row = db.job(&hold.id).await.expect("read").expect("row");
            assert_eq!(row.summary.as_deref(), Some(summary));
            let index = db.result_index(&hold.id).await.expect("index");
            assert_eq!(index, [("plate".to_string(), "plan.zip".to_string())]);
            assert_eq!(kinds(&db, &hold.id).await, ["method"]);
            // The end writes the rest (a landed name again replaces it) and keeps what landed.
            let mut end = finished(1);
            end.files.push(landed_file("plan.zip"));
            assert!(db.finish(&hold.id, "w1", &end).await.expect("finish"));
            assert_eq!(db.result_index(&hold.id).await.expect("index").len(), 2);
            assert_eq!(kinds(&db, &hold.id).await, ["method", "done"]);
        }
    });
}

/// A cancel keeps what landed, and nothing lands after it.
#[test]
fn a_cancel_keeps_what_landed() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let hold = claimed_job(&db, "w1").await;
            assert!(
                db.land(&hold, "{}", &[landed_file("plan.zip")], LANDED)
                    .await
                    .expect("land")
            );
            db.cancel(&hold.id).await.expect("cancel");
            assert!(
                !db.land(&hold, "{}", &[landed_file("late.zip")], LANDED)
                    .await
                    .expect("land")
            );
            assert_eq!(db.result_index(&hold.id).await.expect("index").len(), 1);
            assert_eq!(kinds(&db, &hold.id).await, ["method", "cancelled"]);
        }
    });
}

/// A requeued job (its worker died, or a graceful stop) loses its attempt's results and
/// summary with the retry event, so a retry never mixes its results with its predecessor's;
/// the old attempt can write nothing more, the new one can.
#[test]
fn a_requeue_clears_the_attempts_results() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let first = claimed_job(&db, "w1").await;
            let id = first.id.clone();
            assert!(
                db.land(&first, "{}", &[landed_file("plan.zip")], LANDED)
                    .await
                    .expect("land")
            );
            db.expire_worker("w1").await.expect("expire");
            assert_eq!(db.reap(2).await.expect("reap"), (vec![id.clone()], vec![]));
            assert!(
                db.result_index(&id).await.expect("index").is_empty(),
                "cleared for the retry"
            );
            assert!(db.job(&id).await.expect("read").expect("row").summary.is_none());
            assert!(
                !db.land(&first, "{}", &[landed_file("plan.zip")], LANDED)
                    .await
                    .expect("land")
            );
            let again = db.claim("w2", 60_000).await.expect("claim").expect("job");
            let second = Hold {
                id: id.clone(),
                worker: "w2".into(),
                attempt: again.attempts,
            };
            assert!(
                db.land(&second, "{}", &[landed_file("plan.zip")], LANDED)
                    .await
                    .expect("land")
            );
            assert_eq!(kinds(&db, &id).await, ["method", "retry", "method"]);
            assert_eq!(db.requeue_worker("w2").await.expect("requeue"), 1);
            assert!(
                db.result_index(&id).await.expect("index").is_empty(),
                "a graceful stop too"
            );
        }
    });
}

/// `queue_ahead`: the queued jobs a worker takes first (by creation, then id).
#[test]
fn queue_ahead_counts_the_queued_jobs_taken_first() {
    runtime().block_on(async {
        let dir = tempfile::tempdir().expect("dir");
        for db in databases(&dir).await {
            let t = now_ms();
            let mut jobs = [job(t), job(t + 1), job(t + 1), job(t + 2)];
            jobs[1..3].sort_by(|a, b| a.id.cmp(&b.id));
            for j in jobs.iter().rev() {
                db.insert_job(j).await.expect("insert");
            }
            for (k, j) in jobs.iter().enumerate() {
                assert_eq!(db.queue_ahead(&j.id, j.created).await.expect("ahead"), k as i64);
            }
            db.claim("w1", 60_000).await.expect("claim").expect("job");
            assert_eq!(db.queue_ahead(&jobs[3].id, jobs[3].created).await.expect("ahead"), 2);
        }
    });
}
