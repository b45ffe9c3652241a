#include "native/record_buffer.hpp"

#include <openssl/bio.h>

#include <algorithm>
#include <cstring>
#include <new>

namespace umf::native {

namespace {

int record_buffer_write(BIO* bio, const char* bytes, int n) {
    if (n <= 0) return 0;
    try {
        record_buffer_of(bio).append(bytes, static_cast<std::size_t>(n));
    } catch (const std::bad_alloc&) {
        return -1;
    }
    return n;
}

long record_buffer_ctrl(BIO*, int cmd, long, void*) { return cmd == BIO_CTRL_FLUSH ? 1 : 0; }

int record_buffer_create(BIO* bio) {
    BIO_set_data(bio, new (std::nothrow) RecordBuffer);
    BIO_set_init(bio, BIO_get_data(bio) != nullptr);
    return BIO_get_data(bio) != nullptr;
}

int record_buffer_destroy(BIO* bio) {
    delete static_cast<RecordBuffer*>(BIO_get_data(bio));
    BIO_set_data(bio, nullptr);
    return 1;
}

const BIO_METHOD* record_buffer_method() {
    // Made once for the process, as OpenSSL's own methods are.
    static BIO_METHOD* const method = [] {
        BIO_METHOD* m = BIO_meth_new(BIO_get_new_index() | BIO_TYPE_SOURCE_SINK, "umf record buffer");
        if (m && (BIO_meth_set_write(m, record_buffer_write) != 1 || BIO_meth_set_ctrl(m, record_buffer_ctrl) != 1 ||
                  BIO_meth_set_create(m, record_buffer_create) != 1 ||
                  BIO_meth_set_destroy(m, record_buffer_destroy) != 1)) {
            BIO_meth_free(m);
            m = nullptr;
        }
        return m;
    }();
    return method;
}

}  // namespace

void RecordBuffer::append(const char* bytes, std::size_t n) {
    if (size + n > capacity) {
        const std::size_t grown = std::max(size + n, capacity * 2);
        auto bigger = std::make_unique_for_overwrite<char[]>(grown);
        if (size > 0) std::memcpy(bigger.get(), data.get(), size);
        data = std::move(bigger);
        capacity = grown;
    }
    std::memcpy(data.get() + size, bytes, n);
    size += n;
}

void RecordBuffer::took(std::size_t n) {
    sent += n;
    if (sent == size) size = sent = 0;
}

bio_st* new_record_buffer_bio() {
    const BIO_METHOD* method = record_buffer_method();
    return method ? BIO_new(method) : nullptr;
}

RecordBuffer& record_buffer_of(bio_st* bio) { return *static_cast<RecordBuffer*>(BIO_get_data(bio)); }

}  // namespace umf::native
