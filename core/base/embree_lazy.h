/* Embree 3, opened on first use (lazylib.h): the functions lamina calls,
 * and each name #defined to its pointer, so that code written against
 * <embree3/rtcore.h> stays as it is (rtcInitIntersectContext is inline in
 * the header, not in the library). A call to an Embree function missing
 * from the list fails to link (lamina does not link Embree); one in the
 * list without its #define fails to link the same way, and a #define
 * without its entry does not compile. Include this header, not
 * <embree3/rtcore.h>, and call lam_embree_load before the first Embree
 * call (lam_rays_new does). */
#ifndef LAM_EMBREE_LAZY_H
#define LAM_EMBREE_LAZY_H

#include <embree3/rtcore.h>

#include "lazylib.h"

/* Load Embree (libembree3.so.3, with TBB) if not yet loaded; thread-safe.
 * Errors: LAM_EIO "cannot load libembree3.so.3: ...; install libembree3-3". */
int lam_embree_load(lam_error *err);

#define LAM_EMBREE_FUNCS(X)                  \
    X(rtcAttachGeometry)                     \
    X(rtcCommitGeometry)                     \
    X(rtcCommitScene)                        \
    X(rtcGetDeviceError)                     \
    X(rtcIntersect1)                         \
    X(rtcNewDevice)                          \
    X(rtcNewGeometry)                        \
    X(rtcNewScene)                           \
    X(rtcReleaseDevice)                      \
    X(rtcReleaseGeometry)                    \
    X(rtcReleaseScene)                       \
    X(rtcSetDeviceErrorFunction)             \
    X(rtcSetGeometryBuildQuality)            \
    X(rtcSetGeometryIntersectFilterFunction) \
    X(rtcSetNewGeometryBuffer)               \
    X(rtcSetSceneBuildQuality)               \
    X(rtcSetSceneFlags)

#if LAM_LAZY
LAM_EMBREE_FUNCS(LAM_LAZYLIB_EXTERN)

#define rtcAttachGeometry lam_dl_rtcAttachGeometry
#define rtcCommitGeometry lam_dl_rtcCommitGeometry
#define rtcCommitScene lam_dl_rtcCommitScene
#define rtcGetDeviceError lam_dl_rtcGetDeviceError
#define rtcIntersect1 lam_dl_rtcIntersect1
#define rtcNewDevice lam_dl_rtcNewDevice
#define rtcNewGeometry lam_dl_rtcNewGeometry
#define rtcNewScene lam_dl_rtcNewScene
#define rtcReleaseDevice lam_dl_rtcReleaseDevice
#define rtcReleaseGeometry lam_dl_rtcReleaseGeometry
#define rtcReleaseScene lam_dl_rtcReleaseScene
#define rtcSetDeviceErrorFunction lam_dl_rtcSetDeviceErrorFunction
#define rtcSetGeometryBuildQuality lam_dl_rtcSetGeometryBuildQuality
#define rtcSetGeometryIntersectFilterFunction lam_dl_rtcSetGeometryIntersectFilterFunction
#define rtcSetNewGeometryBuffer lam_dl_rtcSetNewGeometryBuffer
#define rtcSetSceneBuildQuality lam_dl_rtcSetSceneBuildQuality
#define rtcSetSceneFlags lam_dl_rtcSetSceneFlags
#endif

#endif
