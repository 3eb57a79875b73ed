// The real HidBackend: hidapi over Linux hidraw (Debian's libhidapi-dev, hidapi-hidraw).
#include <cerrno>
#include <mutex>

#include <hidapi/hidapi.h>

#include "device/hid_devices.hpp"

namespace echosim::device {
namespace {

// hidapi's process-wide state: hid_init before the first use, hid_exit after the last, and one
// global error string that hid_enumerate and hid_open_path write and hid_error(NULL) reads. Several
// backends (the driver's reader thread, `echosim devices`, tests) may live at once, so they share
// this count, and the mutex also keeps one backend's open-then-read-the-error from interleaving with
// another's. The only global mutable state of the device layer; reads and per-device errors do not
// touch it.
struct HidapiProcess {
    std::mutex mutex;
    int users = 0;
    bool initialised = false;
};

HidapiProcess& hidapi_process()
{
    static HidapiProcess p;
    return p;
}

std::string utf8(const wchar_t* w)
{
    std::string s;
    if (w == nullptr) return s;
    for (; *w != 0; ++w) {
        const auto c = std::uint32_t(*w);
        if (c < 0x80) {
            s += char(c);
        } else if (c < 0x800) {
            s += char(0xc0 | (c >> 6));
            s += char(0x80 | (c & 0x3f));
        } else if (c < 0x10000) {
            s += char(0xe0 | (c >> 12));
            s += char(0x80 | ((c >> 6) & 0x3f));
            s += char(0x80 | (c & 0x3f));
        } else if (c < 0x110000) {
            s += char(0xf0 | (c >> 18));
            s += char(0x80 | ((c >> 12) & 0x3f));
            s += char(0x80 | ((c >> 6) & 0x3f));
            s += char(0x80 | (c & 0x3f));
        }
    }
    return s;
}

class HidapiBackend final : public HidBackend {
public:
    HidapiBackend()
    {
        HidapiProcess& p = hidapi_process();
        const std::lock_guard lock(p.mutex);
        if (p.users++ == 0) p.initialised = hid_init() == 0;
    }
    ~HidapiBackend() override
    {
        HidapiProcess& p = hidapi_process();
        const std::lock_guard lock(p.mutex);
        if (--p.users == 0) {
            hid_exit();
            p.initialised = false;
        }
    }
    HidapiBackend(const HidapiBackend&) = delete;
    HidapiBackend& operator=(const HidapiBackend&) = delete;

    std::vector<HidDeviceInfo> enumerate() override
    {
        HidapiProcess& p = hidapi_process();
        const std::lock_guard lock(p.mutex);
        std::vector<HidDeviceInfo> out;
        if (!p.initialised) return out;
        hid_device_info* list = hid_enumerate(0, 0);
        for (const hid_device_info* d = list; d != nullptr; d = d->next) {
            HidDeviceInfo info;
            info.path = d->path != nullptr ? d->path : "";
            info.vendor_id = d->vendor_id;
            info.product_id = d->product_id;
            info.product = utf8(d->product_string);
            info.serial = utf8(d->serial_number);
            out.push_back(std::move(info));
        }
        hid_free_enumeration(list);
        return out;
    }

    HidOpenResult open(const std::string& path) override
    {
        HidapiProcess& p = hidapi_process();
        const std::lock_guard lock(p.mutex);
        HidOpenResult r;
        if (!p.initialised) {
            r.error = "hid_init failed";
            return r;
        }
        // errno straight after the call is open(2)'s: hidapi only formats its message after it
        errno = 0;
        hid_device* h = hid_open_path(path.c_str());
        const int code = errno;
        if (h != nullptr) {
            r.handle = h;
            return r;
        }
        r.error_code = code;
        r.error = utf8(hid_error(nullptr));
        return r;
    }

    int read(void* handle, std::uint8_t* buffer, std::size_t size, int timeout_ms) override
    {
        return hid_read_timeout(static_cast<hid_device*>(handle), buffer, size, timeout_ms);
    }

    std::string last_error(void* handle) override { return utf8(hid_error(static_cast<hid_device*>(handle))); }

    void close(void* handle) override { hid_close(static_cast<hid_device*>(handle)); }
};

}  // namespace

std::shared_ptr<HidBackend> hidapi_backend()
{
    return std::make_shared<HidapiBackend>();
}

}  // namespace echosim::device
