// TLS records gathered in memory on their way to a socket. OpenSSL hands
// each record (16 KiB at most) to its write BIO as soon as it is sealed;
// through a socket BIO that is a system call a record, 65,536 of them per
// GiB. Through this one the records wait in a buffer the sender empties into
// the socket a quarter of a megabyte or more at a time. (OpenSSL's memory
// BIO would gather them too, but it clears its whole buffer each time it is
// emptied: a megabyte of memset per megabyte sent.)
#pragma once

#include <cstddef>
#include <memory>

struct bio_st;

namespace umf::native {

struct RecordBuffer {
    std::unique_ptr<char[]> data;
    std::size_t capacity = 0;
    std::size_t size = 0;  // written by OpenSSL
    std::size_t sent = 0;  // of those, taken by the socket

    void append(const char* bytes, std::size_t n);
    std::size_t waiting() const { return size - sent; }
    // `n` more bytes went to the socket; the buffer starts again when all did.
    void took(std::size_t n);
};

// A BIO for an SSL object's write side (SSL_set0_wbio, which then owns it)
// that appends to a RecordBuffer of its own; null when OpenSSL cannot make one.
bio_st* new_record_buffer_bio();
// The buffer of a BIO new_record_buffer_bio made.
RecordBuffer& record_buffer_of(bio_st* bio);

}  // namespace umf::native
