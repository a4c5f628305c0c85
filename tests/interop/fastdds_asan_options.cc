// ASan and LSan options of the Fast DDS interop test program only (ASan reads this hook at start-up; an
// ASAN_OPTIONS variable still overrides it flag by flag). Without sanitizers nothing calls it.
//
// new_delete_type_mismatch=0: Debian's libfastrtps 2.9.1 (not instrumented) frees, in
// RTPSReader::~RTPSReader, a 64-byte object that StatisticsReaderImpl's constructor allocated,
// through a 56-byte type (sized delete of a derived object through its base). ASan reports it
// every time a Fast DDS DataReader is deleted (seen here: "new-delete-type-mismatch ...
// RTPSReader::~RTPSReader ... allocated by StatisticsReaderImpl::StatisticsReaderImpl"). It is in
// Fast DDS, not in hubrt; ASan's suppression files cannot name this kind of report, so the check
// is off for this one program. Every other ASan and UBSan check stays on.
// NOLINTNEXTLINE(bugprone-reserved-identifier): the name ASan looks up
extern "C" const char* __asan_default_options() {
  return "new_delete_type_mismatch=0";
}

// LeakSanitizer: blocks allocated inside OpenSSL. This program never calls OpenSSL itself; Fast
// DDS's PKI-DH plugin does, and leaks the X509 certificate it reads from a remote participant
// whose handshake then fails (seen with ASAN_OPTIONS=fast_unwind_on_malloc=0: "Direct leak ...
// d2i_X509_AUX ... PEM_ASN1_read_bio ... PKIDH::begin_handshake_reply ...
// SecurityManager::on_process_handshake"), with everything hanging off it (BN_MONT_CTX_new,
// ASN1_STRING_set, ...). With the default fast unwinder those stacks end inside libcrypto
// (built without frame pointers), so the library is what a suppression can name.
// NOLINTNEXTLINE(bugprone-reserved-identifier): the name LSan looks up
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libcrypto.so\n";
}
