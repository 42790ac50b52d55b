//! `GET /api/conversions/{id}/events`: the server-sent event stream of a conversion.

use std::collections::VecDeque;
use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::{Path, State};
use axum::response::sse::{Event, KeepAlive, Sse};
use futures_util::Stream;

use super::App;
use super::api::load;
use super::error::ApiResult;
use crate::db::EventRow;

/// Events a stream sends at a time.
const EVENT_BATCH: i64 = 200;
/// How often a stream looks for new events.
const EVENT_POLL: Duration = Duration::from_millis(200);

/// `GET /api/conversions/{id}/events`: every event so far, then new ones as workers write
/// them, until `done` or `failed` (polling the events table, which works the same for any
/// number of servers on one database).
pub async fn events(
    State(app): State<Arc<App>>,
    Path(id): Path<String>,
) -> ApiResult<Sse<impl Stream<Item = Result<Event, Infallible>>>> {
    let row = load(&app, &id).await?;
    let state = EventState {
        app,
        id: row.id,
        after: 0,
        pending: VecDeque::new(),
        ended: false,
    };
    let stream = futures_util::stream::unfold(state, next_event);
    Ok(Sse::new(stream).keep_alive(KeepAlive::default()))
}

struct EventState {
    app: Arc<App>,
    id: String,
    after: i64,
    pending: VecDeque<EventRow>,
    ended: bool,
}

/// The last events of a job.
fn is_last(kind: &str) -> bool {
    matches!(kind, "done" | "failed" | "cancelled")
}

async fn next_event(mut s: EventState) -> Option<(Result<Event, Infallible>, EventState)> {
    loop {
        if let Some(e) = s.pending.pop_front() {
            s.after = e.seq;
            s.ended = is_last(&e.kind);
            let event = Event::default().event(e.kind).id(e.seq.to_string()).data(e.data);
            return Some((Ok(event), s));
        }
        if s.ended || *s.app.stopping.borrow() {
            return None;
        }
        match s.app.db.events_after(&s.id, s.after, EVENT_BATCH).await {
            Ok(rows) if !rows.is_empty() => s.pending.extend(rows),
            Ok(_) => {
                // A deleted job has nothing more to say.
                if !matches!(s.app.db.job(&s.id).await, Ok(Some(_))) {
                    return None;
                }
                let mut stopping = s.app.stopping.clone();
                tokio::select! {
                    () = tokio::time::sleep(EVENT_POLL) => {}
                    _ = stopping.changed() => {}
                }
            }
            Err(e) => {
                tracing::error!("events of {}: {e}", s.id);
                return None;
            }
        }
    }
}
