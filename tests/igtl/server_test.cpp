// The live link's server against a client written with the OpenIGTLink library (as 3D Slicer's
// OpenIGTLinkIF is), over loopback only, on a port the system picks (port 0: never one in use).
// What arrives is checked against values worked out by hand from the frame's LPS placement: names,
// types, image size, scalar type, spacing, pixels, and every matrix in Reference (RAS). Then the
// clients' comings and goings: two clients, one gone mid-message, one that stops reading; the other
// keeps being served, publish() never waits; stop() is prompt with a client still connected.
// Where it listens (the loopback interface of both families unless told), a port another program
// holds on IPv6 alone, and what one remote host can hold. Every wait is bounded.
#include "igtl/server.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "igtl/igtl_client.hpp"

namespace echosim::igtl {
namespace {

using namespace std::chrono_literals;
using test::IgtlClient;
using test::IgtlMessage;
using Clock = std::chrono::steady_clock;

// An oblique probe: its axes in world (LPS) have entries in thirds, so every expectation below is
// worked out by hand. Lateral x = (2, 2, 1)/3, beam y = (-2, 1, 2)/3, elevation z = x * y =
// (1, -2, 2)/3; the face at (10, -20, 30) mm. The image: 40 columns of 0.5 mm (20 mm wide, centred
// on the probe), 60 rows of 0.25 mm (15 mm deep), 1 mm thick.
constexpr std::uint32_t kColumns = 40, kRows = 60;
const glm::dvec3 kX = glm::dvec3(2, 2, 1) / 3.0, kY = glm::dvec3(-2, 1, 2) / 3.0, kZ = glm::dvec3(1, -2, 2) / 3.0;
const glm::dvec3 kFace(10, -20, 30);

std::uint8_t pixel_value(std::uint32_t c, std::uint32_t r, int frame) { return std::uint8_t((3 * c + 7 * r + 11 * std::uint32_t(frame)) & 0xffu); }

LiveFrame test_frame(int number = 0, std::uint32_t columns = kColumns, std::uint32_t rows = kRows)
{
    LiveFrame f;
    f.columns = columns;
    f.rows = rows;
    f.pixels.resize(std::size_t(columns) * rows);
    for (std::uint32_t r = 0; r < rows; ++r)
        for (std::uint32_t c = 0; c < columns; ++c) f.pixels[std::size_t(r) * columns + c] = pixel_value(c, r, number);
    f.probe_to_world = glm::dmat4(glm::dvec4(kX, 0), glm::dvec4(kY, 0), glm::dvec4(kZ, 0), glm::dvec4(kFace, 1));
    // pixel (c, r) at the face + x ((c + 0.5) 0.5 - 10) + y (r + 0.5) 0.25
    f.image_to_world = glm::dmat4(glm::dvec4(kX * 0.5, 0), glm::dvec4(kY * 0.25, 0), glm::dvec4(kZ, 0),
                                  glm::dvec4(kFace + kX * (0.25 - 10.0) + kY * 0.125, 1));
    f.timestamp_s = 1.7e9 + number;
    return f;
}

ServerOptions loopback()
{
    ServerOptions o;
    o.port = 0;  // and the default bind: the loopback interface
    return o;
}

void expect_near(const float* got, std::initializer_list<double> want, const char* what, double tolerance = 1e-4)
{
    int i = 0;
    for (double w : want) {
        EXPECT_NEAR(got[i], w, tolerance) << what << "[" << i << "]";
        ++i;
    }
}

// column `c` (0..3) of an OpenIGTLink matrix (float[row][column])
std::array<float, 3> column(const ::igtl::Matrix4x4& m, int c) { return {m[0][c], m[1][c], m[2][c]}; }

// receives until a whole IMAGE, ProbeToReference, ImageToReference set has come (or `limit` messages)
struct FrameSet {
    IgtlMessage image, probe, image_to_reference;
    bool complete() const { return image.image && probe.transform && image_to_reference.transform; }
};
bool receive_set(IgtlClient& client, FrameSet& set, int limit = 12)
{
    set = {};
    for (int i = 0; i < limit && !set.complete(); ++i) {
        IgtlMessage m;
        if (!client.receive(m)) return false;
        if (m.name == kImageName) set.image = m;
        if (m.name == kProbeToReferenceName) set.probe = m;
        if (m.name == kImageToReferenceName) set.image_to_reference = m;
    }
    return set.complete();
}

// the frame number of a received image (pixel (0, 0) is 11 * number mod 256)
int frame_number(const IgtlMessage& m) { return static_cast<const std::uint8_t*>(m.image->GetScalarPointer())[0] * 163 % 256; }

TEST(IgtlServer, SendsTheImageAndTheTransformsInReferenceRas)
{
    Server server(loopback());
    ASSERT_GT(server.port(), 0);
    IgtlClient client(server.port());
    ASSERT_TRUE(client.ok());
    server.publish(test_frame());

    // the three messages of a frame, in order, with their types and names
    IgtlMessage m[3];
    for (IgtlMessage& x : m) ASSERT_TRUE(client.receive(x));
    EXPECT_EQ(m[0].type, "IMAGE");
    EXPECT_EQ(m[0].name, "Image_Reference");
    EXPECT_EQ(m[1].type, "TRANSFORM");
    EXPECT_EQ(m[1].name, "ProbeToReference");
    EXPECT_EQ(m[2].type, "TRANSFORM");
    EXPECT_EQ(m[2].name, "ImageToReference");
    for (const IgtlMessage& x : m) EXPECT_NEAR(x.timestamp_s, 1.7e9, 1e-3);

    // the image: 40 x 60 x 1, uint8, one component, spacing 0.5, 0.25 and the 1 mm thickness, RAS
    ::igtl::ImageMessage& image = *m[0].image;
    int size[3];
    image.GetDimensions(size);
    EXPECT_EQ(size[0], 40);
    EXPECT_EQ(size[1], 60);
    EXPECT_EQ(size[2], 1);
    EXPECT_EQ(image.GetScalarType(), ::igtl::ImageMessage::TYPE_UINT8);
    EXPECT_EQ(image.GetNumComponents(), 1);
    EXPECT_EQ(image.GetCoordinateSystem(), ::igtl::ImageMessage::COORDINATE_RAS);
    float spacing[3];
    image.GetSpacing(spacing);
    expect_near(spacing, {0.5, 0.25, 1.0}, "spacing", 1e-6);
    ASSERT_EQ(image.GetImageSize(), 40 * 60);
    const auto* pixels = static_cast<const std::uint8_t*>(image.GetScalarPointer());
    int wrong = 0;
    for (std::uint32_t r = 0; r < kRows; ++r)
        for (std::uint32_t c = 0; c < kColumns; ++c) wrong += pixels[r * kColumns + c] != pixel_value(c, r, 0);
    EXPECT_EQ(wrong, 0);

    // its placement: the pixel axes in RAS (x and y of the LPS axes negated), and the centre of the
    // pixel grid, pixel (19.5, 29.5): lateral 20 * 0.5 - 10 = 0, depth 30 * 0.25 = 7.5 mm, so LPS
    // (10, -20, 30) + 7.5 (-2, 1, 2)/3 = (5, -17.5, 35), RAS (-5, 17.5, 35)
    ::igtl::Matrix4x4 placement;
    image.GetMatrix(placement);
    expect_near(column(placement, 0).data(), {-2 / 3.0, -2 / 3.0, 1 / 3.0}, "image i");
    expect_near(column(placement, 1).data(), {2 / 3.0, -1 / 3.0, 2 / 3.0}, "image j");
    expect_near(column(placement, 2).data(), {-1 / 3.0, 2 / 3.0, 2 / 3.0}, "image k");
    expect_near(column(placement, 3).data(), {-5, 17.5, 35}, "image centre");
    // as Slicer reads it (OpenIGTLinkIO igtlioConverterUtilities: first pixel = centre - R S (size - 1) / 2):
    // pixel (0, 0) at lateral 0.25 - 10 = -9.75, depth 0.125 mm: LPS (10 - 6.5 - 1/12, -20 - 6.5 + 1/24,
    // 30 - 3.25 + 1/12), RAS (-3.416667, 26.458333, 26.833333)
    float first[3];
    for (int a = 0; a < 3; ++a)
        first[a] = placement[a][3] - placement[a][0] * spacing[0] * float(size[0] - 1) / 2 - placement[a][1] * spacing[1] * float(size[1] - 1) / 2;
    expect_near(first, {-3.416667, 26.458333, 26.833333}, "pixel (0, 0) as Slicer places it");

    // ProbeToReference: the probe's axes and face in RAS
    ::igtl::Matrix4x4 probe;
    m[1].transform->GetMatrix(probe);
    expect_near(column(probe, 0).data(), {-2 / 3.0, -2 / 3.0, 1 / 3.0}, "probe x");
    expect_near(column(probe, 1).data(), {2 / 3.0, -1 / 3.0, 2 / 3.0}, "probe y");
    expect_near(column(probe, 2).data(), {-1 / 3.0, 2 / 3.0, 2 / 3.0}, "probe z");
    expect_near(column(probe, 3).data(), {-10, 20, 30}, "probe face");
    EXPECT_EQ(probe[3][0], 0.0f);
    EXPECT_EQ(probe[3][3], 1.0f);

    // ImageToReference: pixels to RAS mm, scaled by the spacing, from pixel (0, 0)'s centre
    ::igtl::Matrix4x4 to_reference;
    m[2].transform->GetMatrix(to_reference);
    expect_near(column(to_reference, 0).data(), {-1 / 3.0, -1 / 3.0, 1 / 6.0}, "image column step");
    expect_near(column(to_reference, 1).data(), {1 / 6.0, -1 / 12.0, 1 / 6.0}, "image row step");
    expect_near(column(to_reference, 2).data(), {-1 / 3.0, 2 / 3.0, 2 / 3.0}, "image elevation");
    expect_near(column(to_reference, 3).data(), {-3.416667, 26.458333, 26.833333}, "pixel (0, 0)");

    const ServerStats st = server.stats();
    EXPECT_EQ(st.frames_published, 1);
    EXPECT_EQ(st.clients_served, 1);
}

TEST(IgtlServer, KeepsServingOneClientWhileAnotherGoesMidStream)
{
    Server server(loopback());
    IgtlClient first(server.port()), second(server.port());
    ASSERT_TRUE(first.ok());
    ASSERT_TRUE(second.ok());
    // both connected (the server says so) before the stream starts
    std::vector<ServerEvent> events;
    for (const auto until = Clock::now() + 5s; server.stats().clients < 2 && Clock::now() < until;) std::this_thread::sleep_for(5ms);
    ASSERT_EQ(server.stats().clients, 2);

    // the stream, published from another thread at about 100 frames/s; each publish() timed
    std::atomic<bool> streaming{true};
    std::atomic<int> published{0};
    std::atomic<std::int64_t> slowest_publish_us{0};
    std::thread stream([&] {
        for (int n = 0; streaming.load() && n < 2000; ++n) {
            const LiveFrame f = test_frame(n);
            const auto t0 = Clock::now();
            server.publish(f);
            const auto us = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count();
            slowest_publish_us.store(std::max<std::int64_t>(slowest_publish_us.load(), us));
            published.store(n + 1);
            std::this_thread::sleep_for(10ms);
        }
    });

    // both get whole frames
    FrameSet set;
    ASSERT_TRUE(receive_set(first, set));
    ASSERT_TRUE(receive_set(second, set));
    // the first goes in the middle of a message: its header read, its body not
    std::string type;
    ASSERT_TRUE(first.receive_header_only(type));
    first.close();
    const int when_gone = published.load();

    // the second goes on getting frames, each newer than the last (20 frames: their numbers, kept
    // mod 256, do not wrap round to one seen)
    std::vector<int> numbers;
    for (int i = 0; i < 20; ++i) {
        ASSERT_TRUE(receive_set(second, set)) << "after " << i << " frames since the first client went";
        numbers.push_back(frame_number(set.image));
    }
    std::sort(numbers.begin(), numbers.end());
    EXPECT_EQ(std::unique(numbers.begin(), numbers.end()), numbers.end()) << "a frame came twice";
    EXPECT_GT(published.load(), when_gone + 10);

    // the server saw the first go
    bool first_gone = false;
    for (const auto until = Clock::now() + 5s; !first_gone && Clock::now() < until;) {
        server.events(events);
        first_gone = std::any_of(events.begin(), events.end(), [](const ServerEvent& e) { return e.kind == ServerEvent::Kind::disconnected; });
        if (!first_gone) std::this_thread::sleep_for(10ms);
    }
    EXPECT_TRUE(first_gone);
    EXPECT_EQ(server.stats().clients, 1);
    streaming.store(false);
    stream.join();

    // publish() never waited for the network: a copy and a wake-up (bounded loosely: a busy 2-core machine)
    EXPECT_LT(slowest_publish_us.load(), 20000);
    const ServerStats st = server.stats();
    EXPECT_EQ(st.clients_served, 2);
    EXPECT_GT(st.frames_sent, 20);
}

TEST(IgtlServer, DropsAClientThatStopsReadingAndServesTheOthers)
{
    ServerOptions options = loopback();
    options.stall_timeout = 300ms;
    Server server(options);
    IgtlClient stalled(server.port()), reader(server.port());
    ASSERT_TRUE(stalled.ok());
    ASSERT_TRUE(reader.ok());
    for (const auto until = Clock::now() + 5s; server.stats().clients < 2 && Clock::now() < until;) std::this_thread::sleep_for(5ms);
    ASSERT_EQ(server.stats().clients, 2);

    // 1 MB frames, which fill the stalled client's socket buffers within a few frames; the reader
    // reads all along
    std::atomic<bool> streaming{true};
    std::atomic<std::int64_t> slowest_publish_us{0};
    std::thread stream([&] {
        for (int n = 0; streaming.load() && n < 1000; ++n) {
            const LiveFrame f = test_frame(n, 1024, 1024);
            const auto t0 = Clock::now();
            server.publish(f);
            const auto us = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count();
            slowest_publish_us.store(std::max<std::int64_t>(slowest_publish_us.load(), us));
            std::this_thread::sleep_for(10ms);
        }
    });
    std::vector<ServerEvent> events;
    std::string why;
    int sets = 0;
    for (const auto until = Clock::now() + 10s; why.empty() && Clock::now() < until;) {
        FrameSet set;
        ASSERT_TRUE(receive_set(reader, set)) << "the reader was not served while the other client stalled";
        ++sets;
        server.events(events);
        for (const ServerEvent& e : events)
            if (e.kind == ServerEvent::Kind::disconnected) why = e.reason;
    }
    EXPECT_NE(why.find("stalled"), std::string::npos) << "the client that stopped reading was not dropped: " << why;
    // and the reader goes on
    for (int i = 0; i < 5; ++i) {
        FrameSet set;
        ASSERT_TRUE(receive_set(reader, set));
    }
    streaming.store(false);
    stream.join();
    EXPECT_GT(sets, 3);
    EXPECT_LT(slowest_publish_us.load(), 50000);  // a 1 MB copy and a wake-up, never the network
}

TEST(IgtlServer, StopsPromptlyWithAClientConnected)
{
    auto server = std::make_unique<Server>(loopback());
    IgtlClient client(server->port());
    ASSERT_TRUE(client.ok());
    server->publish(test_frame());
    FrameSet set;
    ASSERT_TRUE(receive_set(client, set));
    server->publish(test_frame(1, 1024, 1024));  // on its way, unread, while the server stops
    const auto t0 = Clock::now();
    server->stop();
    EXPECT_LT(Clock::now() - t0, 500ms);
    // the client sees its connection end
    IgtlMessage m;
    int more = 0;
    while (client.receive(m) && more < 10) ++more;
    EXPECT_LT(more, 10);
    server.reset();
}

TEST(IgtlServer, NamesThePortItCannotServe)
{
    Server first(loopback());
    ServerOptions same = loopback();
    same.port = first.port();
    try {
        Server second(same);
        FAIL() << "a second server on port " << same.port;
    } catch (const ServerError& e) {
        EXPECT_NE(std::string(e.what()).find(std::to_string(same.port)), std::string::npos) << e.what();
    }
    ServerOptions out_of_range = loopback();
    out_of_range.port = 70000;
    EXPECT_THROW(Server{out_of_range}, ServerError);
}

// A TCP socket of `family` (AF_INET, AF_INET6) on `address`:`port`, listening (listen) or
// connected to it; -1 when the host cannot (no IPv6). Closed by its owner.
int raw_socket(int family, const char* address, int port, bool listen, bool v6only = true)
{
    const int fd = ::socket(family, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    sockaddr_storage a{};
    socklen_t length = 0;
    if (family == AF_INET) {
        auto& v4 = reinterpret_cast<sockaddr_in&>(a);
        v4.sin_family = AF_INET;
        v4.sin_port = htons(std::uint16_t(port));
        ::inet_pton(AF_INET, address, &v4.sin_addr);
        length = sizeof v4;
    } else {
        auto& v6 = reinterpret_cast<sockaddr_in6&>(a);
        v6.sin6_family = AF_INET6;
        v6.sin6_port = htons(std::uint16_t(port));
        ::inet_pton(AF_INET6, address, &v6.sin6_addr);
        length = sizeof v6;
        const int only = v6only ? 1 : 0;
        ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &only, sizeof only);
    }
    const bool ok = listen ? ::bind(fd, reinterpret_cast<sockaddr*>(&a), length) == 0 && ::listen(fd, 4) == 0
                           : ::connect(fd, reinterpret_cast<sockaddr*>(&a), length) == 0;
    if (!ok) {
        ::close(fd);
        return -1;
    }
    return fd;
}

int bound_port(int fd)
{
    sockaddr_storage a{};
    socklen_t length = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
    return a.ss_family == AF_INET ? ntohs(reinterpret_cast<sockaddr_in&>(a).sin_port) : ntohs(reinterpret_cast<sockaddr_in6&>(a).sin6_port);
}

bool host_has_ipv6_loopback()
{
    const int fd = raw_socket(AF_INET6, "::1", 0, true);
    if (fd < 0) return false;
    ::close(fd);
    return true;
}

// the server's events until `count` of them came (or 5 s went)
std::vector<ServerEvent> wait_for_events(Server& server, std::size_t count)
{
    std::vector<ServerEvent> events;
    for (const auto until = Clock::now() + 5s; events.size() < count && Clock::now() < until;) {
        server.events(events);
        if (events.size() < count) std::this_thread::sleep_for(5ms);
    }
    return events;
}

TEST(IgtlServer, ListensOnTheLoopbackInterfaceOfBothFamiliesByDefault)
{
    Server server(loopback());
    const std::string port = std::to_string(server.port());
    if (!host_has_ipv6_loopback()) {
        EXPECT_EQ(server.listening(), std::vector<std::string>{"127.0.0.1:" + port});
        GTEST_SKIP() << "this host has no IPv6 loopback";
    }
    EXPECT_EQ(server.listening(), (std::vector<std::string>{"127.0.0.1:" + port, "[::1]:" + port}));
    // a client on each family, both served
    IgtlClient v4(server.port());
    ASSERT_TRUE(v4.ok());
    const int v6 = raw_socket(AF_INET6, "::1", server.port(), false);
    ASSERT_GE(v6, 0);
    const std::vector<ServerEvent> events = wait_for_events(server, 2);
    ASSERT_EQ(events.size(), 2u);
    std::vector<std::string> hosts;
    for (const ServerEvent& e : events) {
        EXPECT_EQ(e.kind, ServerEvent::Kind::connected) << e.peer << ": " << e.reason;
        hosts.push_back(e.peer.substr(0, e.peer.rfind(':')));
    }
    std::sort(hosts.begin(), hosts.end());
    EXPECT_EQ(hosts, (std::vector<std::string>{"127.0.0.1", "[::1]"}));
    ::close(v6);
}

TEST(IgtlServer, FindsThePortTakenOnIpv6Alone)
{
    if (!host_has_ipv6_loopback()) GTEST_SKIP() << "this host has no IPv6 loopback";
    // another program serving [::1]:P, IPv6 only (127.0.0.1:P is free): clients that resolve
    // "localhost" to ::1 would reach it, not us
    const int held = raw_socket(AF_INET6, "::1", 0, true);
    ASSERT_GE(held, 0);
    ServerOptions same = loopback();
    same.port = bound_port(held);
    try {
        Server second(same);
        FAIL() << "served port " << same.port << " while another program listens on [::1]:" << same.port;
    } catch (const ServerError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("[::1]:" + std::to_string(same.port)), std::string::npos) << what;
        EXPECT_NE(what.find("in use"), std::string::npos) << what;
    }
    ::close(held);
    // and on every interface, both families ([::], dual stack): refused at 127.0.0.1 already
    const int everywhere = raw_socket(AF_INET6, "::", 0, true, false);
    ASSERT_GE(everywhere, 0);
    same.port = bound_port(everywhere);
    EXPECT_THROW(Server{same}, ServerError);
    ::close(everywhere);
    // and port 0 finds a port free on both
    Server any(loopback());
    EXPECT_EQ(any.listening().size(), 2u);
}

TEST(IgtlServer, ListensWhereItIsToldAndRefusesWhatIsNoAddress)
{
    EXPECT_EQ(bind_address_error("0.0.0.0"), "");
    EXPECT_EQ(bind_address_error("::"), "");
    EXPECT_EQ(bind_address_error("192.168.1.20"), "");
    EXPECT_EQ(bind_address_error("fe80::1"), "");
    for (const char* bad : {"localhost", "", "1.2.3", "256.1.1.1", "::1%lo", "127.0.0.1:18944"})
        EXPECT_NE(bind_address_error(bad).find("not an IPv4 or IPv6 address"), std::string::npos) << bad;

    ServerOptions v4 = loopback();
    v4.bind = "127.0.0.1";
    Server only_v4(v4);
    EXPECT_EQ(only_v4.listening(), std::vector<std::string>{"127.0.0.1:" + std::to_string(only_v4.port())});

    ServerOptions bad = loopback();
    bad.bind = "localhost";
    try {
        Server none(bad);
        FAIL() << "listened on 'localhost'";
    } catch (const ServerError& e) {
        EXPECT_NE(std::string(e.what()).find("'localhost' is not an IPv4 or IPv6 address"), std::string::npos) << e.what();
    }

    if (!host_has_ipv6_loopback()) GTEST_SKIP() << "this host has no IPv6";
    // "::": every interface, both families; an IPv4 client is named by its IPv4 address
    ServerOptions all = loopback();
    all.bind = "::";
    Server everywhere(all);
    EXPECT_EQ(everywhere.listening(), std::vector<std::string>{"[::]:" + std::to_string(everywhere.port())});
    IgtlClient client(everywhere.port());
    ASSERT_TRUE(client.ok());
    const std::vector<ServerEvent> events = wait_for_events(everywhere, 1);
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].kind, ServerEvent::Kind::connected);
    EXPECT_EQ(events[0].peer.rfind("127.0.0.1:", 0), 0u) << events[0].peer;
}

TEST(IgtlServer, LimitsTheClientsOfOneHostAndInAll)
{
    ServerOptions options = loopback();
    options.max_clients_per_host = 2;
    options.max_clients = 3;
    Server server(options);
    server.publish(test_frame());
    IgtlClient a(server.port()), b(server.port()), c(server.port());
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    std::vector<ServerEvent> events = wait_for_events(server, 3);
    ASSERT_EQ(events.size(), 3u);
    int connected = 0;
    std::string refusal;
    for (const ServerEvent& e : events) {
        connected += e.kind == ServerEvent::Kind::connected;
        if (e.kind == ServerEvent::Kind::disconnected) refusal = e.reason;
    }
    EXPECT_EQ(connected, 2);
    EXPECT_EQ(refusal, "refused: already 2 clients from 127.0.0.1");
    EXPECT_EQ(server.stats().clients, 2);
    // the two kept are served; the one refused finds its connection closed
    FrameSet set;
    IgtlMessage m;
    int got = 0;
    got += receive_set(a, set);
    got += receive_set(b, set);
    got += receive_set(c, set);
    EXPECT_EQ(got, 2) << "two clients of the three served";

    if (!host_has_ipv6_loopback()) GTEST_SKIP() << "this host has no IPv6: the limit in all is not tried";
    // another address (::1) may connect, up to the limit in all
    const int v6 = raw_socket(AF_INET6, "::1", server.port(), false);
    const int v6_more = raw_socket(AF_INET6, "::1", server.port(), false);
    ASSERT_GE(v6, 0);
    ASSERT_GE(v6_more, 0);
    events = wait_for_events(server, 2);
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].kind, ServerEvent::Kind::connected);
    EXPECT_EQ(events[1].kind, ServerEvent::Kind::disconnected);
    EXPECT_EQ(events[1].reason, "refused: already 3 clients");
    EXPECT_EQ(server.stats().clients, 3);
    ::close(v6);
    ::close(v6_more);
}

TEST(IgtlServer, RefusesFramesThatDoNotHoldTogether)
{
    Server server(loopback());
    LiveFrame short_of_pixels = test_frame();
    short_of_pixels.pixels.pop_back();
    EXPECT_THROW(server.publish(short_of_pixels), std::invalid_argument);
    LiveFrame flat = test_frame();
    flat.image_to_world[1] = glm::dvec4(0.0);
    EXPECT_THROW(server.publish(flat), std::invalid_argument);
    EXPECT_EQ(server.stats().frames_published, 0);
}

}  // namespace
}  // namespace echosim::igtl
