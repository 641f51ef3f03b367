//! Automatic fit (placeholder).
