//! Step `labels`: part and connection numbers engraved as single-stroke text.
