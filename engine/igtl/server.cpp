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
#include <cstring>
#include <memory>

#include "igtl/messages.hpp"

namespace echosim::igtl {
namespace {

using Clock = std::chrono::steady_clock;
using Bytes = std::shared_ptr<const std::vector<std::byte>>;

constexpr std::size_t kMaxQueuedEvents = 1024;  // the oldest go first when the caller never drains
constexpr int kPollMs = 100;                    // how often a stalled client is looked at [ms]

std::string error_text(int error) { return std::strerror(error); }

std::string peer_name(const sockaddr_in& addr)
{
    char text[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &addr.sin_addr, text, sizeof text);
    return std::string(text) + ":" + std::to_string(ntohs(addr.sin_port));
}

// One connected client, owned by the network thread.
struct Client {
    int fd = -1;
    std::string peer;
    Bytes sending;                     // the frame on its way to it (null: it has all it was given)
    std::size_t offset = 0;            // bytes of `sending` it has taken
    std::uint64_t given_sequence = 0;  // the frame last given to it
    std::int64_t frames = 0;           // frames it was sent whole
    Clock::time_point last_progress;
};

// Reads and discards what the client sent; "" while it is there, else why it is gone.
std::string drain(const Client& c)
{
    std::byte scrap[4096];
    for (;;) {
        const ssize_t n = ::recv(c.fd, scrap, sizeof scrap, MSG_DONTWAIT);
        if (n > 0) continue;
        if (n == 0) return "closed the connection";
        if (errno == EINTR) continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) return "";
        return "receive failed: " + error_text(errno);
    }
}

}  // namespace

Server::Server(const ServerOptions& options) : options_(options)
{
    const auto fail = [&](const std::string& what, int error) {
        const std::string text = "OpenIGTLink port " + std::to_string(options_.port) + ": " + what + ": " + error_text(error);
        if (listen_fd_ >= 0) ::close(listen_fd_);
        if (wake_fd_ >= 0) ::close(wake_fd_);
        listen_fd_ = wake_fd_ = -1;
        return ServerError(text);
    };
    if (options_.port < 0 || options_.port > 65535) throw ServerError("OpenIGTLink port " + std::to_string(options_.port) + ": not in 0..65535");
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (listen_fd_ < 0) throw fail("cannot make a socket", errno);
    const int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(std::uint16_t(options_.port));
    addr.sin_addr.s_addr = htonl(options_.loopback_only ? INADDR_LOOPBACK : INADDR_ANY);
    if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) throw fail("cannot listen there", errno);
    if (::listen(listen_fd_, 8) != 0) throw fail("cannot listen there", errno);
    socklen_t length = sizeof addr;
    if (::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &length) != 0) throw fail("cannot read the bound port", errno);
    port_ = ntohs(addr.sin_port);
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
    if (listen_fd_ >= 0) ::close(listen_fd_);
    if (wake_fd_ >= 0) ::close(wake_fd_);
    listen_fd_ = wake_fd_ = -1;
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
    const auto accept_all = [&](Clock::time_point now) {
        for (;;) {
            sockaddr_in addr{};
            socklen_t length = sizeof addr;
            const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
            if (fd < 0) {
                if (errno == EINTR || errno == ECONNABORTED) continue;
                return;  // none left (EAGAIN), or out of descriptors: the next poll tries again
            }
            std::string peer = peer_name(addr);
            if (int(clients.size()) >= options_.max_clients) {
                ::close(fd);
                post({ServerEvent::Kind::disconnected, std::move(peer),
                      "refused: already " + std::to_string(options_.max_clients) + " clients", 0, int(clients.size())});
                continue;
            }
            const int one = 1;
            ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
            clients.push_back({fd, peer, nullptr, 0, 0, 0, now});
            clients_served_.fetch_add(1);
            clients_.fetch_add(1);
            post({ServerEvent::Kind::connected, std::move(peer), "", 0, clients_.load()});
        }
    };

    try {
        while (!stopping_.load()) {
            fds.clear();
            fds.push_back({wake_fd_, POLLIN, 0});
            fds.push_back({listen_fd_, POLLIN, 0});
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
                const short events = fds[i + 2].revents;
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
            if (fds[1].revents & POLLIN) accept_all(now);
        }
    } catch (const std::exception& e) {
        post({ServerEvent::Kind::error, "", std::string("the network thread stopped: ") + e.what(), 0, 0});
    }
    for (Client& c : clients)
        if (c.fd >= 0) drop(c, "the server stopped");
}

}  // namespace echosim::igtl
