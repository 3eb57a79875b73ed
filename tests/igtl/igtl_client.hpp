// A test client of the live link written with the OpenIGTLink library itself (as 3D Slicer's
// OpenIGTLinkIF is): connects over loopback, receives whole messages with a timeout and unpacks them
// with the CRC checked.
#pragma once

#include <chrono>
#include <string>
#include <thread>

#include <igtlClientSocket.h>
#include <igtlImageMessage.h>
#include <igtlMessageHeader.h>
#include <igtlTransformMessage.h>

namespace echosim::test {

struct IgtlMessage {
    std::string type, name;
    double timestamp_s = 0;
    ::igtl::ImageMessage::Pointer image;          // type IMAGE
    ::igtl::TransformMessage::Pointer transform;  // type TRANSFORM
};

class IgtlClient {
public:
    // Connects to 127.0.0.1:`port`, trying for up to 5 s. `ok()` says whether it did.
    explicit IgtlClient(int port)
    {
        socket_ = ::igtl::ClientSocket::New();
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (socket_->ConnectToServer("127.0.0.1", port) != 0) {
            if (std::chrono::steady_clock::now() > until) return;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        socket_->SetReceiveTimeout(5000);  // [ms] each receive waits at most this long
        connected_ = true;
    }

    bool ok() const { return connected_; }
    void close() { socket_->CloseSocket(); }

    // The next whole message; false when none came within the receive timeout or it did not unpack.
    bool receive(IgtlMessage& out)
    {
        ::igtl::MessageHeader::Pointer header = ::igtl::MessageHeader::New();
        header->InitPack();
        if (!receive_all(header->GetPackPointer(), header->GetPackSize())) return false;
        header->Unpack();
        out = {header->GetDeviceType(), header->GetDeviceName(), 0, nullptr, nullptr};
        ::igtl::TimeStamp::Pointer time = ::igtl::TimeStamp::New();
        header->GetTimeStamp(time);
        out.timestamp_s = time->GetTimeStamp();
        ::igtl::MessageBase::Pointer body;
        if (out.type == "IMAGE") {
            out.image = ::igtl::ImageMessage::New();
            body = out.image;
        } else if (out.type == "TRANSFORM") {
            out.transform = ::igtl::TransformMessage::New();
            body = out.transform;
        } else {
            body = ::igtl::MessageBase::New();
        }
        body->SetMessageHeader(header);
        body->AllocatePack();
        if (!receive_all(body->GetPackBodyPointer(), body->GetPackBodySize())) return false;
        return (body->Unpack(1) & ::igtl::MessageHeader::UNPACK_BODY) != 0 || body->GetPackBodySize() == 0;
    }

    // Only the next message's header (the rest stays unread: a client gone mid-message).
    bool receive_header_only(std::string& type)
    {
        ::igtl::MessageHeader::Pointer header = ::igtl::MessageHeader::New();
        header->InitPack();
        if (!receive_all(header->GetPackPointer(), header->GetPackSize())) return false;
        header->Unpack();
        type = header->GetDeviceType();
        return true;
    }

private:
    bool receive_all(void* data, int length)
    {
        if (length == 0) return true;
        return socket_->Receive(data, length) == length;
    }

    ::igtl::ClientSocket::Pointer socket_;
    bool connected_ = false;
};

}  // namespace echosim::test
