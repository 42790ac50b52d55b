//! PostgreSQL's `LISTEN`: wakes the hub's poller the moment a worker commits an event, so
//! events reach clients without waiting for the next poll. Polling stays the fallback: when
//! the listening connection fails, the hub polls until it is back.

use std::sync::Arc;
use std::time::Duration;

use sqlx::postgres::PgListener;
use tokio::sync::watch;

use super::hub::Hub;
use crate::db::dialect::EVENTS_CHANNEL;

/// How long to wait before listening again after the connection failed.
const RECONNECT: Duration = Duration::from_secs(1);

/// Listens on the events channel of the database at `url` until `stopping`; each
/// notification (a job id) marks that job for the poller.
pub(crate) async fn run(hub: Arc<Hub>, url: String, mut stopping: watch::Receiver<bool>) {
    loop {
        tokio::select! {
            result = listen(&hub, &url) => {
                hub.listening.send_replace(false);
                if let Err(e) = result {
                    tracing::warn!("listening for new events: {e}; polling meanwhile");
                }
            }
            _ = stopping.wait_for(|s| *s) => return,
        }
        tokio::select! {
            () = tokio::time::sleep(RECONNECT) => {}
            _ = stopping.wait_for(|s| *s) => return,
        }
    }
}

/// One listening connection, until it fails.
async fn listen(hub: &Hub, url: &str) -> Result<(), sqlx::Error> {
    let mut listener = PgListener::connect(url).await?;
    listener.listen(EVENTS_CHANNEL).await?;
    hub.listening.send_replace(true);
    // Events committed while no connection listened are found by the timer's polls.
    loop {
        let notification = listener.recv().await?;
        hub.mark_urgent(notification.payload());
    }
}
