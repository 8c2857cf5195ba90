#include "access/login_limiter.hpp"

namespace rotord::access {
LoginLimiter::Entry* LoginLimiter::find(const Peer& peer) {
  for (Entry& e : entries_)
    if (e.used && e.who.same_host(peer)) return &e;
  return nullptr;
}

const LoginLimiter::Entry* LoginLimiter::find(const Peer& peer) const {
  for (const Entry& e : entries_)
    if (e.used && e.who.same_host(peer)) return &e;
  return nullptr;
}

Millis LoginLimiter::wait_ms(const Peer& peer, Millis now) const {
  const Entry* e = find(peer);
  if (e == nullptr || e->blocked_until <= now) return 0;
  return e->blocked_until - now;
}

unsigned LoginLimiter::failed(const Peer& peer, Millis now) {
  Entry* e = find(peer);
  if (e == nullptr) {
    e = &entries_[0];
    for (Entry& candidate : entries_) {
      if (!candidate.used) {
        e = &candidate;
        break;
      }
      if (candidate.last < e->last) e = &candidate;
    }
    *e = Entry{};
    e->used = true;
    e->who = peer;
  }
  ++e->failures;
  e->last = now;
  if (e->failures >= kFreeFailures) {
    Millis wait = kFirstWaitMs;
    for (unsigned n = kFreeFailures; n < e->failures && wait < kMaxWaitMs; ++n) wait *= 2;
    e->blocked_until = now + (wait < kMaxWaitMs ? wait : kMaxWaitMs);
  }
  return e->failures;
}

void LoginLimiter::succeeded(const Peer& peer) {
  if (Entry* e = find(peer)) *e = Entry{};
}

}  // namespace rotord::access
