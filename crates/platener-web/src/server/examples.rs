//! The shipped examples: queued and published on the first start, so the gallery is never
//! empty. Embedded in the binary, so a server needs no checkout.

use crate::db::{Db, NewJob, Result, now_ms};
use crate::ids;
use crate::settings::JobSettings;

/// The examples/ folder of the repository: name and bytes.
pub const EXAMPLES: [(&str, &[u8]); 3] = [
    ("box-3mm.stl", include_bytes!("../../../../examples/box-3mm.stl")),
    (
        "phone-stand.stl",
        include_bytes!("../../../../examples/phone-stand.stl"),
    ),
    ("tray-3mm.stl", include_bytes!("../../../../examples/tray-3mm.stl")),
];

/// Queues and publishes the examples unless a server did before (on this database). Their
/// delete tokens are thrown away: only the database's operator removes them.
pub async fn seed(db: &Db) -> Result<()> {
    if !db.set_meta_once("examples_seeded", "1").await? {
        return Ok(());
    }
    let settings = serde_json::to_string(&JobSettings::default()).unwrap_or_default();
    let now = now_ms();
    for (i, (name, bytes)) in EXAMPLES.iter().enumerate() {
        let job = NewJob {
            id: ids::conversion_id(),
            name: (*name).to_string(),
            model: bytes.to_vec(),
            triangles: None,
            settings: settings.clone(),
            created: now,
            delete_token_hash: ids::hash_token(&ids::token()),
            // Newest first in the gallery: the box, the first example, shows first.
            published: Some(now - i64::try_from(i).unwrap_or(0)),
            parent: None,
        };
        db.insert_job(&job).await?;
    }
    Ok(())
}
