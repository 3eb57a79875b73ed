#include "igtl/server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>

#include "igtl/messages.hpp"

namespace echosim::igtl {
namespace {

using Clock = std::chrono::steady_clock;
using Bytes = std::shared_ptr<const std::vector<std::byte>>;

constexpr std::size_t kMaxQueuedEvents = 1024;  // the oldest go first when the caller never drains
constexpr int kPollMs = 100;                    // how often a stalled client is looked at [ms]
constexpr std::size_t kMaxDrainBytes = 64 * 1024;  // read from one client a round, at most [bytes]
constexpr int kMaxAcceptsPerRound = 32;
constexpr int kPortTries = 8;  // port 0 on two addresses: free on the first, taken on the second

std::string error_text(int error) { return std::strerror(error); }

// An address to listen on, its port still to be set.
struct Endpoint {
    sockaddr_storage addr{};
    socklen_t length = 0;
    bool v6only = true;      // IPv6: its own family only ("::" serves both)
    bool optional = false;   // skipped where the host has no such address (::1 without IPv6)
};

std::optional<Endpoint> parse_endpoint(const std::string& text)
{
    Endpoint e;
    auto* v4 = reinterpret_cast<sockaddr_in*>(&e.addr);
    auto* v6 = reinterpret_cast<sockaddr_in6*>(&e.addr);
    if (::inet_pton(AF_INET, text.c_str(), &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        e.length = sizeof(sockaddr_in);
        return e;
    }
    if (::inet_pton(AF_INET6, text.c_str(), &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        e.length = sizeof(sockaddr_in6);
        e.v6only = !IN6_IS_ADDR_UNSPECIFIED(&v6->sin6_addr);
        return e;
    }
    return std::nullopt;
}

void set_port(Endpoint& e, int port)
{
    if (e.addr.ss_family == AF_INET)
        reinterpret_cast<sockaddr_in*>(&e.addr)->sin_port = htons(std::uint16_t(port));
    else
        reinterpret_cast<sockaddr_in6*>(&e.addr)->sin6_port = htons(std::uint16_t(port));
}

int port_of(const sockaddr_storage& a)
{
    return a.ss_family == AF_INET ? ntohs(reinterpret_cast<const sockaddr_in&>(a).sin_port) : ntohs(reinterpret_cast<const sockaddr_in6&>(a).sin6_port);
}

// The address of a socket's end without its port ("10.0.0.5", "::1"); an IPv4 client reaching an
// IPv6 socket ("::ffff:10.0.0.5") as its IPv4 address, so it counts as one host either way.
std::string host_text(const sockaddr_storage& a)
{
    char text[INET6_ADDRSTRLEN] = "?";
    if (a.ss_family == AF_INET) {
        ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in&>(a).sin_addr, text, sizeof text);
    } else if (a.ss_family == AF_INET6) {
        const in6_addr& v6 = reinterpret_cast<const sockaddr_in6&>(a).sin6_addr;
        if (IN6_IS_ADDR_V4MAPPED(&v6))
            ::inet_ntop(AF_INET, &v6.s6_addr[12], text, sizeof text);
        else
            ::inet_ntop(AF_INET6, &v6, text, sizeof text);
    }
    return text;
}

// "10.0.0.5:50123", "[::1]:50123"
std::string endpoint_text(const sockaddr_storage& a)
{
    const std::string host = host_text(a);
    return (host.find(':') != std::string::npos ? "[" + host + "]" : host) + ":" + std::to_string(port_of(a));
}

// One connected client, owned by the network thread.
struct Client {
    int fd = -1;
    std::string peer;
    std::string host;                  // its address, without the port: what max_clients_per_host counts
    Bytes sending;                     // the frame on its way to it (null: it has all it was given)
    std::size_t offset = 0;            // bytes of `sending` it has taken
    std::uint64_t given_sequence = 0;  // the frame last given to it
    std::int64_t frames = 0;           // frames it was sent whole
    Clock::time_point last_progress;
};

// Reads and discards what the client sent (at most kMaxDrainBytes: the rest waits for the next
// round); "" while it is there, else why it is gone.
std::string drain(const Client& c)
{
    std::byte scrap[4096];
    for (std::size_t taken = 0; taken < kMaxDrainBytes;) {
        const ssize_t n = ::recv(c.fd, scrap, sizeof scrap, MSG_DONTWAIT);
        if (n > 0) {
            taken += std::size_t(n);
            continue;
        }
        if (n == 0) return "closed the connection";
        if (errno == EINTR) continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) return "";
        return "receive failed: " + error_text(errno);
    }
    return "";
}

// A listening socket on `e`, or -1 with errno set.
int listen_on(const Endpoint& e)
{
    const int fd = ::socket(e.addr.ss_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    const int one = 1, v6only = e.v6only ? 1 : 0;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (e.addr.ss_family == AF_INET6) ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &v6only, sizeof v6only);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&e.addr), e.length) != 0 || ::listen(fd, 8) != 0) {
        const int error = errno;
        ::close(fd);
        errno = error;
        return -1;
    }
    return fd;
}

}  // namespace

std::string bind_address_error(const std::string& address)
{
    if (parse_endpoint(address)) return "";
    return "'" + address + "' is not an IPv4 or IPv6 address (127.0.0.1 or ::1: this machine; 0.0.0.0: every IPv4 interface; ::: every interface)";
}

Server::Server(const ServerOptions& options) : options_(options)
{
    const std::string port_text = "OpenIGTLink port " + std::to_string(options_.port);
    const auto close_all = [&] {
        for (const int fd : listen_fds_) ::close(fd);
        listen_fds_.clear();
        listening_.clear();
    };
    const auto fail = [&](const std::string& what, int error) {
        close_all();
        if (wake_fd_ >= 0) ::close(wake_fd_);
        wake_fd_ = -1;
        return ServerError(port_text + ": " + what + ": " + error_text(error));
    };
    if (options_.port < 0 || options_.port > 65535) throw ServerError(port_text + ": not in 0..65535");
    if (options_.max_clients < 1 || options_.max_clients_per_host < 1) throw ServerError(port_text + ": a client limit below 1");
    std::vector<Endpoint> endpoints;
    if (options_.bind.empty()) {
        endpoints = {*parse_endpoint("127.0.0.1"), *parse_endpoint("::1")};
        endpoints[1].optional = true;
    } else {
        const std::optional<Endpoint> e = parse_endpoint(options_.bind);
        if (!e) throw ServerError(port_text + ": bind address " + bind_address_error(options_.bind));
        endpoints = {*e};
    }
    // every address on one port: the one asked for, or (port 0) the first address's free one, tried
    // again should another program hold it on a later address
    for (int attempt = 1;; ++attempt) {
        int port = options_.port;
        bool retry = false;
        for (Endpoint& e : endpoints) {
            set_port(e, port);
            const int fd = listen_on(e);
            if (fd < 0) {
                const int error = errno;
                if (e.optional && (error == EADDRNOTAVAIL || error == EAFNOSUPPORT)) continue;  // a host without IPv6
                if (options_.port == 0 && port != 0 && error == EADDRINUSE && attempt < kPortTries) {
                    retry = true;
                    break;
                }
                throw fail(endpoint_text(e.addr) + ": cannot listen there", error);
            }
            listen_fds_.push_back(fd);
            sockaddr_storage bound{};
            socklen_t length = sizeof bound;
            if (::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length) != 0) throw fail("cannot read the bound port", errno);
            listening_.push_back(endpoint_text(bound));
            port = port_of(bound);
        }
        if (!retry) {
            port_ = port;
            break;
        }
        close_all();
    }
    wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (wake_fd_ < 0) throw fail("cannot make the wake-up eventfd", errno);
    thread_ = std::thread(&Server::run, this);
}

Server::~Server() { stop(); }

void Server::stop()
{
    if (thread_.joinable()) {
        stopping_.store(true);
        const std::uint64_t one = 1;
        [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
        thread_.join();
    }
    for (const int fd : listen_fds_) ::close(fd);
    listen_fds_.clear();
    if (wake_fd_ >= 0) ::close(wake_fd_);
    wake_fd_ = -1;
}

void Server::publish(const LiveFrame& frame)
{
    check_frame(frame);
    Published& slot = latest_.write_slot();
    slot.frame = frame;  // the slot's vector keeps its storage once it has the frame's size
    slot.sequence = ++sequence_;
    latest_.publish();
    frames_published_.fetch_add(1, std::memory_order_relaxed);
    if (wake_fd_ >= 0) {
        // an eventfd write only fails when its counter would overflow: a wake-up is pending then
        const std::uint64_t one = 1;
        [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
    }
}

void Server::post(ServerEvent event)
{
    const std::lock_guard lock(events_mutex_);
    if (events_.size() >= kMaxQueuedEvents) events_.erase(events_.begin());
    events_.push_back(std::move(event));
}

void Server::events(std::vector<ServerEvent>& out)
{
    const std::lock_guard lock(events_mutex_);
    out.insert(out.end(), std::make_move_iterator(events_.begin()), std::make_move_iterator(events_.end()));
    events_.clear();
}

ServerStats Server::stats() const
{
    return {frames_published_.load(), frames_sent_.load(), clients_served_.load(), clients_.load()};
}

void Server::run()
{
    std::vector<Client> clients;
    std::vector<pollfd> fds;
    Bytes packed;  // the newest frame, packed once for every client
    std::uint64_t packed_sequence = 0;

    const auto drop = [&](Client& c, std::string reason) {
        ::close(c.fd);
        c.fd = -1;
        clients_.fetch_sub(1);
        post({ServerEvent::Kind::disconnected, c.peer, std::move(reason), c.frames, clients_.load()});
    };
    // sends the client what it can take now, and the newest frame once it has had all of one;
    // "" while it is fine, else why it goes
    const auto feed = [&](Client& c, Clock::time_point now) -> std::string {
        for (;;) {
            if (!c.sending) {
                if (!packed || c.given_sequence == packed_sequence) return "";
                c.sending = packed;
                c.offset = 0;
                c.given_sequence = packed_sequence;
                c.last_progress = now;
            }
            const std::vector<std::byte>& bytes = *c.sending;
            const ssize_t n = ::send(c.fd, bytes.data() + c.offset, bytes.size() - c.offset, MSG_NOSIGNAL | MSG_DONTWAIT);
            if (n > 0) {
                c.offset += std::size_t(n);
                c.last_progress = now;
                if (c.offset == bytes.size()) {
                    c.sending.reset();
                    ++c.frames;
                    frames_sent_.fetch_add(1, std::memory_order_relaxed);
                }
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
                if (now - c.last_progress <= options_.stall_timeout) return "";
                char text[80];
                std::snprintf(text, sizeof text, "stalled: took no data for %.1f s",
                              std::chrono::duration<double>(options_.stall_timeout).count());
                return text;
            }
            return "send failed: " + error_text(n < 0 ? errno : EPIPE);
        }
    };
    // accepts what waits on one listening socket (at most kMaxAcceptsPerRound), refusing a client
    // over either limit at once
    const auto accept_from = [&](int listen_fd, Clock::time_point now) {
        for (int accepted = 0; accepted < kMaxAcceptsPerRound; ++accepted) {
            sockaddr_storage addr{};
            socklen_t length = sizeof addr;
            const int fd = ::accept4(listen_fd, reinterpret_cast<sockaddr*>(&addr), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
            if (fd < 0) {
                if (errno == EINTR || errno == ECONNABORTED) continue;
                return;  // none left (EAGAIN), or out of descriptors: the next poll tries again
            }
            std::string peer = endpoint_text(addr), host = host_text(addr);
            const auto from_host = std::count_if(clients.begin(), clients.end(), [&](const Client& c) { return c.host == host; });
            std::string refusal;
            if (int(clients.size()) >= options_.max_clients)
                refusal = "refused: already " + std::to_string(options_.max_clients) + " clients";
            else if (from_host >= options_.max_clients_per_host)
                refusal = "refused: already " + std::to_string(options_.max_clients_per_host) + " clients from " + host;
            if (!refusal.empty()) {
                ::close(fd);
                post({ServerEvent::Kind::disconnected, std::move(peer), std::move(refusal), 0, int(clients.size())});
                continue;
            }
            const int one = 1;
            ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
            clients.push_back({fd, peer, std::move(host), nullptr, 0, 0, 0, now});
            clients_served_.fetch_add(1);
            clients_.fetch_add(1);
            post({ServerEvent::Kind::connected, std::move(peer), "", 0, clients_.load()});
        }
    };

    try {
        while (!stopping_.load()) {
            fds.clear();
            fds.push_back({wake_fd_, POLLIN, 0});
            for (const int fd : listen_fds_) fds.push_back({fd, POLLIN, 0});
            const std::size_t first_client = fds.size();
            for (const Client& c : clients) fds.push_back({c.fd, short(POLLIN | (c.sending ? POLLOUT : 0)), 0});
            if (::poll(fds.data(), fds.size(), kPollMs) < 0 && errno != EINTR) {
                post({ServerEvent::Kind::error, "", "the network thread stopped: poll failed: " + error_text(errno), 0, 0});
                break;
            }
            if (stopping_.load()) break;
            if (fds[0].revents & POLLIN) {
                std::uint64_t count = 0;
                [[maybe_unused]] const ssize_t n = ::read(wake_fd_, &count, sizeof count);
            }
            const Clock::time_point now = Clock::now();

            // the newest frame, packed once; a client gets it as soon as it has all of the last
            const Published& latest = latest_.read();
            if (latest.sequence != packed_sequence) {
                packed = std::make_shared<const std::vector<std::byte>>(pack_frame(latest.frame));
                packed_sequence = latest.sequence;
            }
            // the clients polled (those accepted below wait for the next round)
            for (std::size_t i = 0; i < clients.size(); ++i) {
                Client& c = clients[i];
                const short events = fds[first_client + i].revents;
                std::string gone;
                if (events & POLLIN) gone = drain(c);
                if (gone.empty() && (events & (POLLERR | POLLHUP))) {
                    int error = 0;
                    socklen_t length = sizeof error;
                    ::getsockopt(c.fd, SOL_SOCKET, SO_ERROR, &error, &length);
                    gone = error ? "connection failed: " + error_text(error) : "closed the connection";
                }
                if (gone.empty()) gone = feed(c, now);
                if (!gone.empty()) drop(c, std::move(gone));
            }
            std::erase_if(clients, [](const Client& c) { return c.fd < 0; });
            // newcomers are sent the newest frame from the next round on (at the next publish, or
            // within kPollMs)
            for (std::size_t l = 0; l < listen_fds_.size(); ++l)
                if (fds[1 + l].revents & POLLIN) accept_from(listen_fds_[l], now);
        }
    } catch (const std::exception& e) {
        post({ServerEvent::Kind::error, "", std::string("the network thread stopped: ") + e.what(), 0, 0});
    }
    for (Client& c : clients)
        if (c.fd >= 0) drop(c, "the server stopped");
}

}  // namespace echosim::igtl
