// The live link's server (`echosim run --igtl [PORT]`), as PlusServer serves 3D Slicer: every
// frame the caller publishes goes to every connected OpenIGTLink client (live_frame.hpp: the
// messages, their names and frames). Clients connect and go as they like.
//
// Threads and hand-offs.
//   - The caller's thread (the run loop, at the display rate) calls publish(), events(), stats().
//     publish() never waits for the network: it copies the frame into a lock-free triple buffer
//     (core/triple_buffer.hpp: latest wins, frames the network has not taken yet are overwritten)
//     and wakes the network thread through an eventfd (a non-blocking write).
//   - One network thread, started by the constructor and joined by stop(), owns the listening
//     socket and every client: it waits in poll() on the wake-up, the listening socket and the
//     clients; accepts; takes the newest frame, packs it once (messages.hpp) and sends those bytes
//     to each client. The client list lives on that thread alone, so it needs no lock.
//   - What the caller learns of the network (a client came, a client went) crosses back through
//     a small mutex-guarded queue that the network thread appends to between its I/O and the
//     caller drains with events(); counters are atomics.
//
// A client costs the others nothing. Sockets are non-blocking and sent to with MSG_NOSIGNAL (so a
// client that vanished gives EPIPE, never a SIGPIPE that would kill the process; the OpenIGTLink
// library's own Socket::Send passes no such flag, which is one reason the server speaks POSIX
// sockets and uses the library for the messages only). Each client has its own position in the
// frame it is being sent: a slow one is sent what it can take whenever poll() says it can take
// more, and once it has all of a frame it gets the newest (frames in between are skipped for it,
// not for the others). A client that takes no byte for `stall_timeout` (2 s) is dropped, as is one
// whose send fails or that closed its end. What clients send is read and discarded (PlusServer
// answers commands; we have none).
//
// Binding: the loopback interface by default, 127.0.0.1 and ::1 (where the host has IPv6), so only
// this machine can connect: the link has no authentication, and PlusServer's habit of listening on
// every interface hands the probe's images to anyone on the network. Serving 3D Slicer on another
// machine is asked for by address (ServerOptions::bind, `--igtl-bind`): an IPv4 or IPv6 literal,
// "0.0.0.0" for every IPv4 interface, "::" for every interface of both families. Listening on both
// loopback families also means a port another program holds on either is found: a PlusServer on
// [::1]:18944 would otherwise take the clients that resolve "localhost" to ::1 while we served
// 127.0.0.1 alone. The address is reused (SO_REUSEADDR), so a restart right after a run does not find
// the port held by connections still closing; a port another program listens on, on any of the
// addresses, is refused with the port and the address named.
//
// What one remote host can hold: at most max_clients_per_host connections from one address (an
// IPv4 client reaching "::" counts as its IPv4 address) and max_clients in all; more are accepted
// and closed at once, said as a refusal. Each client costs at most one packed frame in memory (the
// one it is being sent, shared with the others; frames it has not taken are skipped, never
// queued) plus the kernel's socket buffer, and a client that takes nothing for `stall_timeout` is
// dropped. What a client sends is read and discarded, at most 64 KiB a client each round of the
// network thread, and at most 32 connections are accepted a round, so neither a flood of bytes nor
// one of connections keeps the thread from the other clients (server.cpp: kMaxDrainBytes,
// kMaxAcceptsPerRound).
//
// stop() is prompt: the wake-up ends the network thread's poll at once; clients still connected are
// closed.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/triple_buffer.hpp"
#include "igtl/live_frame.hpp"

namespace echosim::igtl {

struct ServerOptions {
    int port = kDefaultPort;  // 0: any free port (port() says which; the same on every address)
    // where to listen: "" the loopback interface (127.0.0.1 and ::1), this machine alone; else one
    // IPv4 or IPv6 literal ("0.0.0.0": every IPv4 interface; "::": every interface, both families)
    std::string bind;
    std::chrono::milliseconds stall_timeout{2000};  // a client taking no data this long is dropped
    int max_clients = 16;                           // in all; more are accepted and closed at once
    int max_clients_per_host = 4;                   // from one remote address; more likewise
};

// "" when `address` can be ServerOptions::bind (an IPv4 or IPv6 literal), else why it cannot.
std::string bind_address_error(const std::string& address);

// The port cannot be served (in use, not permitted, ...): what() names the port and the reason.
class ServerError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ServerEvent {
    // error: the network thread met what it cannot go on from (the link is down; `reason` says why)
    enum class Kind { connected, disconnected, error };
    Kind kind = Kind::connected;
    std::string peer;       // address:port of the client
    std::string reason;     // disconnected, error: why ("closed the connection", "send failed: ...", "stalled ...")
    std::int64_t frames = 0;  // disconnected: frames it was sent whole
    int clients = 0;        // clients connected after the event
};

struct ServerStats {
    std::int64_t frames_published = 0;  // publish() calls
    std::int64_t frames_sent = 0;       // frames sent whole, summed over the clients
    std::int64_t clients_served = 0;    // clients accepted since the start
    int clients = 0;                    // connected now
};

class Server {
public:
    // Binds, listens and starts the network thread. Throws ServerError naming the port (and the
    // address that could not be had, or the bind address that is none).
    explicit Server(const ServerOptions& options = {});
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    int port() const { return port_; }  // the port served (the one asked for, or the free one chosen for 0)
    // where it listens, address and port: "127.0.0.1:18944", "[::1]:18944"
    const std::vector<std::string>& listening() const { return listening_; }

    // Hands the frame to the network thread, which sends it (or a newer one) to every client. Never
    // blocks on the network; copies the pixels (no allocation once the buffers have the frame's
    // size). Throws std::invalid_argument for a frame that does not hold together (messages.hpp).
    void publish(const LiveFrame& frame);

    // Appends what happened since the last call (clients connected and gone), oldest first.
    void events(std::vector<ServerEvent>& out);
    ServerStats stats() const;

    // Closes every client and the listening socket and joins the network thread; also on destruction.
    void stop();

private:
    struct Published {
        LiveFrame frame;
        std::uint64_t sequence = 0;  // 0: nothing published yet
    };
    void run();  // the network thread
    void post(ServerEvent event);

    ServerOptions options_;
    int port_ = 0;
    std::vector<int> listen_fds_;
    std::vector<std::string> listening_;
    int wake_fd_ = -1;  // eventfd: publish() and stop() wake the network thread
    TripleBuffer<Published> latest_;
    std::uint64_t sequence_ = 0;  // the caller's: the last frame published
    std::atomic<bool> stopping_{false};
    std::atomic<std::int64_t> frames_published_{0}, frames_sent_{0}, clients_served_{0};
    std::atomic<int> clients_{0};
    std::mutex events_mutex_;
    std::vector<ServerEvent> events_;  // guarded by events_mutex_
    std::thread thread_;               // last: started once everything above exists
};

}  // namespace echosim::igtl
