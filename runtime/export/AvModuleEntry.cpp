// The one symbol geokiosk-av.so exports (everything else is hidden): StreamModule.cpp finds it
// with dlsym.
#include "runtime/export/AvStream.h"

extern "C" __attribute__((visibility("default"))) kiosk::video::EncoderStream*
kiosk_video_make_stream() {
    return new kiosk::video::AvStream();
}
