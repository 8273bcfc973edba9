//! frozen_bubble (in progress).
