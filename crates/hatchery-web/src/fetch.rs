//! Files of the figure folder, fetched over HTTP (the page's origin: any static server).

use js_sys::Uint8Array;
use wasm_bindgen::{JsCast, JsError};
use wasm_bindgen_futures::JsFuture;
use web_sys::Response;

/// The folder part of a URL, with its trailing slash (`a/b/figure.json` → `a/b/`).
pub fn folder_of(url: &str) -> String {
    match url.rfind('/') {
        Some(i) => url[..=i].to_owned(),
        None => String::new(),
    }
}

/// A relative path as a URL: each segment percent-encoded (`#`, `?`, `%` in file names).
pub fn encode_path(path: &str) -> String {
    path.split('/')
        .map(|segment| String::from(js_sys::encode_uri_component(segment)))
        .collect::<Vec<_>>()
        .join("/")
}

async fn response(url: &str) -> Result<Response, JsError> {
    let window = web_sys::window().ok_or_else(|| JsError::new("no window"))?;
    let fail =
        |e: wasm_bindgen::JsValue| JsError::new(&format!("{url}: cannot fetch: {}", describe(&e)));
    let response: Response = JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(fail)?
        .dyn_into()
        .map_err(fail)?;
    if !response.ok() {
        return Err(JsError::new(&format!(
            "{url}: the server answered {} {}",
            response.status(),
            response.status_text()
        )));
    }
    Ok(response)
}

/// The bytes at `url`. Errors: unreachable, or an HTTP error status, naming the URL.
pub async fn bytes(url: &str) -> Result<Vec<u8>, JsError> {
    let response = response(url).await?;
    let fail = |e: wasm_bindgen::JsValue| JsError::new(&format!("{url}: {}", describe(&e)));
    let buffer = JsFuture::from(response.array_buffer().map_err(fail)?)
        .await
        .map_err(fail)?;
    Ok(Uint8Array::new(&buffer).to_vec())
}

/// The text at `url` (UTF-8).
pub async fn text(url: &str) -> Result<String, JsError> {
    String::from_utf8(bytes(url).await?)
        .map_err(|e| JsError::new(&format!("{url}: not UTF-8 text: {e}")))
}

/// Lets the page's event loop run for about `ms` milliseconds (GPU promises resolve there).
pub async fn sleep_ms(ms: i32) -> Result<(), wasm_bindgen::JsValue> {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(window) = web_sys::window() {
            let _ = window.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, ms);
        }
    });
    JsFuture::from(promise).await.map(drop)
}

fn describe(value: &wasm_bindgen::JsValue) -> String {
    value
        .as_string()
        .or_else(|| {
            value
                .dyn_ref::<js_sys::Error>()
                .map(|e| String::from(e.message()))
        })
        .unwrap_or_else(|| format!("{value:?}"))
}
