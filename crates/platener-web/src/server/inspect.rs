//! The upload-time reading of a model: before a job is stored, the server reads the model with
//! the library's own `read` step, so an unreadable model is a `422` with the reader's message
//! (line or triangle) at once rather than a failed job later, and the `202` already has the
//! model's triangles and bounding box.
//!
//! Reading is the only model work the server does. It is bounded: the upload and its triangles
//! are already within the limits ([`crate::sniff`]), a 3MF may unpack to at most
//! [`UNPACK_FACTOR`] times the upload limit, and at most one model per core is read at a time
//! on blocking threads, so the async runtime keeps answering. A reader that panics gives a
//! `422` too; the worker still fails a job whose model it cannot read (jobs stored before this
//! check, or by other servers).

use std::io::{self, Read as _};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, LazyLock};

use platener::context::StepContext;
use platener::{Cancel, Settings, Source};
use tokio::sync::Semaphore;

use super::error::{ApiError, ApiResult};
use crate::sniff::{Refusal, safe_message, within_triangles};

/// A 3MF may unpack to this many times the upload limit (its XML compresses about tenfold;
/// a ZIP bomb unpacks a thousandfold).
pub const UNPACK_FACTOR: u64 = 10;

/// What the reading found, for the `202`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inspected {
    /// Triangles read.
    pub triangles: u64,
    /// The bounding box's size in mm, after the upload's units and scale.
    pub bbox_mm: [f64; 3],
}

/// What reading may use.
#[derive(Debug, Clone, Copy)]
pub struct ReadLimits {
    /// The most triangles a model may have.
    pub max_triangles: u64,
    /// The most bytes a 3MF's entries may unpack to.
    pub max_unpacked: u64,
}

/// One permit per core: models read at once beyond that would only wait for a core while
/// holding their memory.
static READERS: LazyLock<Arc<Semaphore>> = LazyLock::new(|| {
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get);
    Arc::new(Semaphore::new(cores))
});

/// Reads `model` (named `name`, whose extension picks the reader) on a blocking thread once a
/// core is free; gives the model back with what was found, or the refusal as an API error.
pub async fn read(
    name: String,
    model: Vec<u8>,
    settings: Settings,
    limits: ReadLimits,
) -> ApiResult<(Vec<u8>, Inspected)> {
    let permit = READERS
        .clone()
        .acquire_owned()
        .await
        .map_err(|_| ApiError::internal())?;
    let (model, outcome) = tokio::task::spawn_blocking(move || {
        // The permit is held by the thread, so a request dropped by its timeout cannot let
        // more readers run than there are cores.
        let _permit = permit;
        let outcome = inspect(&name, &model, &settings, limits);
        (model, outcome)
    })
    .await
    .map_err(|_| ApiError::internal())?;
    Ok((model, outcome?))
}

/// Reads a model as the worker's `read` step will: the same reader, units and scale.
pub fn inspect(name: &str, model: &[u8], settings: &Settings, limits: ReadLimits) -> Result<Inspected, Refusal> {
    if name.ends_with(".3mf") {
        unpacked_within(model, limits.max_unpacked)?;
    }
    let source = Source::Bytes {
        name: name.to_string(),
        bytes: Arc::from(model),
    };
    let cancel = Cancel::default();
    let read = catch_unwind(AssertUnwindSafe(|| {
        let mut cx = StepContext::new("read", name, &cancel);
        platener::read::run(&source, settings, &mut cx)
    }));
    let model = match read {
        Ok(Ok(model)) => model,
        Ok(Err(e)) => return Err(Refusal::Unreadable(safe_message(&e.to_string()))),
        Err(_) => {
            tracing::error!(model = name, "the reader panicked");
            return Err(Refusal::Unreadable(
                "the model could not be read: the reader failed on it (a bug in platener; please \
                 report it with the file), so export it again, perhaps in another format"
                    .into(),
            ));
        }
    };
    let triangles = u64::try_from(model.triangles.len()).unwrap_or(u64::MAX);
    within_triangles(triangles, limits.max_triangles)?;
    let size = model.bounds.size();
    Ok(Inspected {
        triangles,
        bbox_mm: [size.x, size.y, size.z],
    })
}

/// Refuses a 3MF (a ZIP) whose entries unpack to more than `max` bytes, counting as it unpacks
/// (the sizes a ZIP declares may lie). A ZIP the `zip` crate cannot open or unpack is left to
/// the reader, which uses the same crate and says what is wrong in its own words.
fn unpacked_within(model: &[u8], max: u64) -> Result<(), Refusal> {
    let Ok(mut archive) = zip::ZipArchive::new(io::Cursor::new(model)) else {
        return Ok(());
    };
    let mut total: u64 = 0;
    for i in 0..archive.len() {
        let Ok(entry) = archive.by_index(i) else {
            return Ok(());
        };
        let left = max - total;
        let Ok(n) = io::copy(&mut entry.take(left + 1), &mut io::sink()) else {
            return Ok(());
        };
        total += n;
        if total > max {
            return Err(Refusal::TooLarge(format!(
                "the 3MF unpacks to more than {} MB, which this server does not read; simplify \
                 the model or upload it as a binary STL",
                max as f64 / 1e6
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::io::Write as _;

    use super::*;

    const LIMITS: ReadLimits = ReadLimits {
        max_triangles: 1000,
        max_unpacked: 100_000,
    };

    /// A ZIP with one deflated entry of `size` zero bytes.
    fn zip_of_zeros(name: &str, size: usize) -> Vec<u8> {
        let mut out = io::Cursor::new(Vec::new());
        let mut zip = zip::ZipWriter::new(&mut out);
        let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
        zip.start_file(name, options).expect("entry");
        zip.write_all(&vec![0u8; size]).expect("write");
        zip.finish().expect("finish");
        out.into_inner()
    }

    const TETRA: &str = "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 10 0 0\nvertex 0 20 0\n\
endloop\nendfacet\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 20 0\nvertex 0 0 30\nendloop\nendfacet\nendsolid t\n";

    #[test]
    fn a_readable_model_gives_its_triangles_and_box_in_mm() {
        let found = inspect("t.stl", TETRA.as_bytes(), &Settings::default(), LIMITS).expect("reads");
        assert_eq!(found.triangles, 2);
        assert_eq!(found.bbox_mm, [10.0, 20.0, 30.0]);
        let cm = Settings {
            units: platener::Units::Cm,
            ..Settings::default()
        };
        assert_eq!(
            inspect("t.stl", TETRA.as_bytes(), &cm, LIMITS).expect("reads").bbox_mm,
            [100.0, 200.0, 300.0]
        );
        let one = ReadLimits {
            max_triangles: 1,
            ..LIMITS
        };
        assert!(matches!(
            inspect("t.stl", TETRA.as_bytes(), &Settings::default(), one),
            Err(Refusal::TooLarge(m)) if m.contains("2 triangles")
        ));
    }

    #[test]
    fn the_readers_message_is_kept_without_markup() {
        let bad = TETRA.replace("vertex 10 0 0", "vertex <b>&0 0");
        let Err(Refusal::Unreadable(m)) = inspect("t.stl", bad.as_bytes(), &Settings::default(), LIMITS) else {
            panic!("refused as unreadable");
        };
        assert!(m.starts_with("t.stl: line 5: "), "{m}");
        assert!(m.contains("?b??0"), "{m}");
        assert!(!m.contains('<') && !m.contains('&'), "{m}");
    }

    #[test]
    fn a_3mf_that_unpacks_past_the_limit_is_refused_before_reading() {
        let bomb = zip_of_zeros("3D/3dmodel.model", 200_000);
        assert!(bomb.len() < 1000, "{} bytes", bomb.len());
        assert!(matches!(
            inspect("b.3mf", &bomb, &Settings::default(), LIMITS),
            Err(Refusal::TooLarge(m)) if m.contains("unpacks to more than 0.1 MB")
        ));
        // Within the limit it is read, and the reader says what is wrong with it.
        let small = zip_of_zeros("3D/3dmodel.model", 1000);
        assert!(matches!(
            inspect("b.3mf", &small, &Settings::default(), LIMITS),
            Err(Refusal::Unreadable(m)) if m.starts_with("b.3mf: 3MF: ")
        ));
        assert!(
            unpacked_within(b"PK\x03\x04 not a zip", 10).is_ok(),
            "left to the reader"
        );
    }
}
