//! `GET /api/conversions/{id}/events`: the server-sent event stream of a conversion.
//!
//! Streams read their job's events from the process's [`Hub`], which reads the database for
//! all of them at once ([`hub`]); the events table stays the one source, so any number of
//! servers on one database stream the same events.

mod hub;
mod listen;
#[cfg(test)]
mod tests;

use std::convert::Infallible;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::{Path, State};
use axum::response::sse::{Event, KeepAlive, Sse};
use futures_util::Stream;

use super::App;
use super::api::load;
use super::error::ApiResult;

pub(crate) use hub::{Hub, Subscription};

/// How often the hub reads the new events of every watched job (on PostgreSQL a fallback:
/// notifications wake it at once).
pub(crate) const EVENT_POLL: Duration = Duration::from_millis(200);

/// `GET /api/conversions/{id}/events`: every event so far, then new ones as workers write
/// them, until `done`, `failed` or `cancelled`, the job's deletion or the server's shutdown.
pub async fn events(
    State(app): State<Arc<App>>,
    Path(id): Path<String>,
) -> ApiResult<Sse<impl Stream<Item = Result<Event, Infallible>>>> {
    let row = load(&app, &id).await?;
    let subscription = Subscription::new(app.events.subscribe(&row.id), app.stopping.clone());
    let stream = futures_util::stream::unfold(subscription, |mut s| async move {
        let e = s.next().await?;
        let event = Event::default().event(e.kind).id(e.seq.to_string()).data(e.data);
        Some((Ok(event), s))
    });
    Ok(Sse::new(stream).keep_alive(KeepAlive::default()))
}
