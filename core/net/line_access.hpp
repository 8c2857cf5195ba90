#pragma once
#include "access/peer.hpp"
#include "settings/settings.hpp"

// In net/, beside the connection admission, because it reads the settings'
// network lists: the rest of access/ (credentials, sessions, the control
// lock) sits below the settings, which check the credentials' text formats.
// The name stays access::may_control, as the sessions call it.
namespace rotord::access {

/// Whether a line-protocol client (WRC, rotctld, GS-232, Easycomm, seed) may
/// change anything: move, park, reset, speed, settings. STOP is never asked:
/// anyone allowed to connect may stop the rotator. Read from the settings at
/// each command, so a changed allow-list applies to connected clients at once.
///
/// - the access settings could not be read at start-up
///   (Settings::access_unreadable): nobody, on any port;
/// - access.control_networks empty: every client controls (the default, as
///   before access control);
/// - otherwise a network client controls when its address is in one of the
///   networks (IPv4 or IPv6; an IPv4 client of a dual-stack socket,
///   ::ffff:a.b.c.d, matches the IPv4 entries); a client whose address is
///   unknown never does;
/// - pty, serial and USB ports control when access.serial_control is on.
bool may_control(const settings::Settings& settings, const Peer& peer);

}  // namespace rotord::access
