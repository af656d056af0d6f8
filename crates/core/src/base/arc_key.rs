//! A cache key that names one shared value by its identity.
//!
//! Keying a cache by `Arc::as_ptr(&a) as usize` is wrong once `a` is dropped: the next
//! value can be allocated at the same address and the cache takes it for the old one (a
//! flaky, allocator-dependent stale hit). An [`ArcKey`] holds a [`Weak`] to the value, so
//! that address is not given out again while the key lives (the value itself is dropped
//! with its last `Arc`; only its small allocation stays): equal keys are the same value.

use std::fmt;
use std::sync::{Arc, Weak};

/// The identity of one `Arc`'s value (see the module).
pub struct ArcKey<T: ?Sized>(Weak<T>);

impl<T: ?Sized> ArcKey<T> {
    /// The key of `value`.
    pub fn of(value: &Arc<T>) -> Self {
        Self(Arc::downgrade(value))
    }

    /// Whether `value` is the one this key names.
    pub fn is(&self, value: &Arc<T>) -> bool {
        std::ptr::addr_eq(self.0.as_ptr(), Arc::as_ptr(value))
    }
}

/// The identity of one `Arc`'s value, whatever its type: one key type for what holds
/// values of several types (the layers a renderer was given).
pub type AnyKey = ArcKey<dyn std::any::Any + Send + Sync>;

impl AnyKey {
    /// The key of `value`.
    pub fn of_any<T: std::any::Any + Send + Sync>(value: &Arc<T>) -> Self {
        let value: Arc<dyn std::any::Any + Send + Sync> = value.clone();
        Self(Arc::downgrade(&value))
    }

    /// Whether `value` is the one this key names (as [`ArcKey::is`], for any type).
    pub fn is_any<T: std::any::Any + Send + Sync>(&self, value: &Arc<T>) -> bool {
        std::ptr::addr_eq(self.0.as_ptr(), Arc::as_ptr(value))
    }
}

impl<T: ?Sized> Clone for ArcKey<T> {
    fn clone(&self) -> Self {
        Self(self.0.clone())
    }
}

impl<T: ?Sized> PartialEq for ArcKey<T> {
    fn eq(&self, other: &Self) -> bool {
        Weak::ptr_eq(&self.0, &other.0)
    }
}

impl<T: ?Sized> Eq for ArcKey<T> {}

impl<T: ?Sized> fmt::Debug for ArcKey<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "ArcKey({:p})", self.0.as_ptr())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_value_at_the_old_address_is_not_the_old_one() {
        let first = Arc::new([7u64; 4]);
        let key = ArcKey::of(&first);
        assert!(key.is(&first));
        assert_eq!(key, ArcKey::of(&first));
        drop(first);
        // Many allocations of the same size: the allocator would hand the freed block
        // out again at once were the key not holding it.
        let later: Vec<Arc<[u64; 4]>> = (0..64).map(|_| Arc::new([7u64; 4])).collect();
        assert!(later.iter().all(|a| !key.is(a) && key != ArcKey::of(a)));
    }

    /// A key of any type names the value as its typed key does: the same value, the same
    /// key, whatever the type; another value at the freed address, another key.
    #[test]
    fn an_any_key_is_the_value_s_identity() {
        let first = Arc::new([3u32; 8]);
        let key = AnyKey::of_any(&first);
        assert_eq!(key, AnyKey::of_any(&first));
        assert!(key.is_any(&first));
        assert_ne!(key, AnyKey::of_any(&Arc::new([3u32; 8])));
        drop(first);
        let later: Vec<Arc<[u32; 8]>> = (0..64).map(|_| Arc::new([3u32; 8])).collect();
        assert!(
            later
                .iter()
                .all(|a| key != AnyKey::of_any(a) && !key.is_any(a))
        );
    }
}
